// Verify: the CGAL Delaunay verifier on a rectangle of a world (plus its 2 d
// halo), reported field by field; a field world's by the field verifier, a
// layered world's by the layered verifier.
#include <algorithm>
#include <cmath>

#include "scallop/plane/world_layers.h"
#include "scallop/plane/world_verifier.h"
#include "server/region_warmup.h"
#include "server/request_cost.h"
#include "server/scallop_service.h"
#include "server/status_mapping.h"
#include "verify_messages.h"
#include "world_messages.h"

namespace scallop::server {

grpc::ServerUnaryReactor* ScallopService::Verify(grpc::CallbackServerContext* context,
                                                 const v1::VerifyRequest* request,
                                                 v1::VerifyResponse* response) {
  const grpc::Status auth = shared_.Authorize(*context, *request);
  return RunUnary(
      context, "Verify", auth, RequestCost(shared_.worlds, *request),
      [this, context, request, response](RequestLog& log) {
        World world;
        Rect rect;
        if (grpc::Status status = shared_.ResolveQuery(*request, shared_.config.max_verify_area,
                                                       "max_verify_area", log, world, rect);
            !status.ok()) {
          return status;
        }
        // The rectangle and its halo generated a block at a time, so a client
        // that goes stops the generation, and then the verifier too.
        // A rectangle the rule refuses is left to VerifyWorldRect to report.
        const QueryLimit limit{.max_area = shared_.config.max_verify_area,
                               .name = "max_verify_area"};
        const WorldLayers* layers = world.layers();
        const double halo =  // VerifyWorldRect's
            layers != nullptr ? std::max(2 * layers->largest_spacing(), layers->largest_exclusion())
                              : 2 * world.max_spacing();
        if (const Rect grown = Grown(rect, halo);
            CheckQueryRect(world, grown, limit, "rect+halo").ok()) {
          if (grpc::Status status =
                  WarmRegions(shared_.engine, world, grown, StopWhenGone(context));
              !status.ok()) {
            return status;
          }
        }
        StatusOr<VerifyReport> report = VerifyWorldRect(shared_.engine, world, rect, limit,
                                                        /*inside=*/nullptr, StopWhenGone(context));
        if (!report.ok()) return ToGrpcStatus(report.status());
        const double max_abs =
            std::max({std::abs(rect.x0), std::abs(rect.x1), std::abs(rect.y0), std::abs(rect.y1)}) +
            halo;
        *response->mutable_world() = shared_.worlds.ToMessage(world);
        response->set_points_checked(report->points_checked);
        response->set_pairs_checked(report->pairs_checked);
        response->set_min_distance(report->min_distance);
        response->set_spacing_violations(report->spacing_violations);
        response->set_largest_empty_circle(report->largest_empty_circle);
        response->set_largest_empty_centre_x(report->largest_empty_centre.x);
        response->set_largest_empty_centre_y(report->largest_empty_centre.y);
        response->set_pairs_across_seams(report->pairs_across_seams);
        response->set_min_distance_across_seams(report->min_distance_across_seams);
        response->set_spacing_violations_across_seams(report->spacing_violations_across_seams);
        response->set_spacing_ok(report->spacing_ok);
        response->set_maximal_ok(report->maximal_ok);
        if (report->field) *response->mutable_field() = FieldVerifyToMessage(*report->field);
        if (report->layered) {
          std::vector<std::string> names;
          for (int k = 0; k < world.layers()->count(); ++k)
            names.push_back(world.layers()->name(k));
          *response->mutable_layered() = LayeredVerifyToMessage(*report->layered, names);
        }
        response->set_maximality_tolerance(MaximalityTolerance(world.min_distance(), max_abs));
        response->set_passed(report->passed());
        log.add_points(report->points_checked);
        return grpc::Status::OK;
      });
}

}  // namespace scallop::server
