// Conversions between the API's messages (scallop.v1.World, Rect, Points) and
// the core's value types, shared by scallopd and the client library so both
// read the proto's defaults (density 0, generator_version 0) the same way.
#pragma once

#include <span>
#include <vector>

#include "raster_catalog.h"
#include "scallop/base/status.h"
#include "scallop/field/radius_field.h"
#include "scallop/geometry/rect.h"
#include "scallop/plane/plane_engine.h"
#include "scallop/plane/world.h"
#include "scallop/v1/scallop.pb.h"

namespace scallop {

// The message's world, with its zero defaults filled in, validated
// (World::Create). INVALID_ARGUMENT naming the field (world.algorithm,
// world.density, world.min_distance, world.generator_version, and a radius
// field's as RadiusFieldFromMessage names them: world.radius_field.noise.r_min,
// world.radius_field.raster.raster_name...) otherwise. A raster field's name
// is looked up in `rasters` (null: none loaded, so every raster name is
// unknown). Cost: O(1); a raster field O(pixels) (its checks and mask table).
StatusOr<World> WorldFromMessage(const v1::World& message, const RasterCatalog* rasters = nullptr);

// The spec WorldFromMessage hands World::Create: the zero defaults filled in, each radius field
// read (RadiusFieldFromMessage) with its errors named under `where` (`where`.radius_field...,
// `where`.layers[k].radius_field...; "world" for a request, a config's key for YAML), the
// rest left to World::Create. INVALID_ARGUMENT naming `where`.algorithm for an unknown one.
StatusOr<WorldSpec> WorldSpecFromMessage(const v1::World& message, const RasterCatalog* rasters,
                                         const std::string& where = "world");

// The world as a message, every field explicit (no zero defaults left); a
// raster field by its name and pixel hash in `rasters` (null, or an image
// it does not hold: the name left empty).
v1::World WorldToMessage(const World& world, const RasterCatalog* rasters = nullptr);
// A spec as a message, field for field, valid or not: what a client sends
// for the server to judge (a raster field without its name, which the
// caller sets: the spec holds only pixels).
v1::World WorldToMessage(const WorldSpec& spec);

// Field-for-field; the range checks are CheckQueryRect's (query_rect.h).
Rect RectFromMessage(const v1::Rect& message);
v1::Rect RectToMessage(const Rect& rect);

// Points [begin, end) of `points` appended to the packed arrays of `message`;
// with a field (a field world's), each point's R in radii as well.
void AppendPoints(const PlanePoints& points, size_t begin, size_t end, v1::Points& message,
                  const RadiusField* field = nullptr);

// Whether a layered world's points carry radii: some layer has a radius field
// (then every point's spacing in its layer goes with it, d for a constant layer).
bool LayeredPointsCarryRadii(const World& world);

// Appends points to the packed arrays of a message through plain pointers:
// room for `capacity` points is made up front, and the destructor cuts the
// arrays to the points appended. (add_xs() and the like check the capacity
// and store the size for every element, three times a point; that copy was
// 15% of a warm server's time.) Use the message only after the appender is
// gone. With a field (a field world's, null otherwise), each point's R goes
// into radii too (one evaluation a point). REQUIRES: at most `capacity`
// calls of Append.
class PointsAppender {
 public:
  PointsAppender(v1::Points& message, size_t capacity, const RadiusField* field = nullptr);
  // Any world's points: a plain or field world's as above; a layered world's
  // with each point's layer in layers (StartLayer says which) and, when
  // LayeredPointsCarryRadii, its spacing in radii.
  PointsAppender(v1::Points& message, size_t capacity, const World& world);
  ~PointsAppender();
  PointsAppender(const PointsAppender&) = delete;
  PointsAppender& operator=(const PointsAppender&) = delete;

  // The points appended next are layer `layer`'s (-1: the world has no layers; nothing
  // changes). REQUIRES: the layered world's constructor for layer >= 0.
  void StartLayer(int layer);

  void Append(Vec2 position, uint64_t id) {
    xs_[count_] = position.x;
    ys_[count_] = position.y;
    ids_[count_] = id;
    if (field_ != nullptr) {
      radii_[count_] = field_->Evaluate(position);
    } else if (layer_world_ != nullptr) {
      if (radii_ != nullptr) radii_[count_] = layer_world_->SpacingAt(position);
      layers_[count_] = layer_;
    }
    ++count_;
  }
  size_t count() const { return count_; }

 private:
  void Reserve(size_t capacity, bool radii, bool layers);

  v1::Points& message_;
  int start_;  // the arrays' size before
  double* xs_;
  double* ys_;
  uint64_t* ids_;
  const RadiusField* field_;
  double* radii_ = nullptr;
  const World* world_ = nullptr;        // a layered world's
  const World* layer_world_ = nullptr;  // the current layer's world (a layered world's)
  uint32_t* layers_ = nullptr;
  uint32_t layer_ = 0;
  // Not size_t: a store to ids_ (uint64_t, the same type as size_t here) could
  // alias it, so GCC reloaded and stored it between points, and a warm tile's
  // copy waited on that chain (bench/warm_answer_bench.cc). A message holds
  // fewer than 2^31 points.
  uint32_t count_ = 0;
};

// The message's points appended to `points`, and its radii to `radii` when
// given, from the packed arrays or, when set, decoded from encoded
// (encoded_points.h), so callers need not know which the request asked for.
// A layered world's layers go to points.layers (from layers, or from each
// encoded region's layer); for other worlds points.layers is left alone.
// INVALID_ARGUMENT when xs, ys and ids differ in length, radii or layers is
// neither empty nor one per point, a layer exceeds 255, both encoded and the
// packed arrays are set, or encoded is malformed (naming its field).
Status ReadPoints(const v1::Points& message, PlanePoints& points,
                  std::vector<double>* radii = nullptr);

}  // namespace scallop
