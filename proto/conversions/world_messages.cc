// World, rectangle and point conversions between scallop.v1 messages and the core.
#include "world_messages.h"

#include <algorithm>
#include <string>

#include "encoded_points.h"
#include "field_messages.h"
#include "scallop/plane/world_layers.h"

namespace scallop {

StatusOr<WorldSpec> WorldSpecFromMessage(const v1::World& message, const RasterCatalog* rasters,
                                         const std::string& where) {
  WorldSpec spec;
  spec.seed = message.seed();
  spec.min_distance = message.min_distance();
  switch (message.algorithm()) {
    case v1::ALGORITHM_A1:
      spec.algorithm = WorldAlgorithm::kA1;
      break;
    case v1::ALGORITHM_A2:
      spec.algorithm = WorldAlgorithm::kA2;
      break;
    case v1::ALGORITHM_A3:
      spec.algorithm = WorldAlgorithm::kA3;
      break;
    default:
      return InvalidArgument(
          where + ".algorithm: must be ALGORITHM_A1, ALGORITHM_A2 or ALGORITHM_A3, got " +
          std::to_string(message.algorithm()));
  }
  // proto3 cannot tell an unset double from 0, and 0 is never a valid density
  // or version, so 0 safely means "the default".
  spec.density = message.density() == 0.0 ? 2.0 : message.density();
  spec.generator_version =
      message.generator_version() == 0 ? kGeneratorVersion : message.generator_version();
  const RasterCatalog none;
  const RasterCatalog& catalog = rasters != nullptr ? *rasters : none;
  if (message.has_radius_field()) {
    StatusOr<RadiusFieldSpec> field =
        RadiusFieldFromMessage(message.radius_field(), catalog, where + ".radius_field");
    if (!field.ok()) return field.status();
    spec.radius_field = std::move(*field);
  }
  for (int k = 0; k < message.layers_size(); ++k) {
    const v1::Layer& layer = message.layers(k);
    LayerSpec own{.name = layer.name(), .min_distance = layer.min_distance()};
    if (layer.has_radius_field()) {
      StatusOr<RadiusFieldSpec> field = RadiusFieldFromMessage(
          layer.radius_field(), catalog, where + ".layers[" + std::to_string(k) + "].radius_field");
      if (!field.ok()) return field.status();
      own.radius_field = std::move(*field);
    }
    spec.layers.push_back(std::move(own));
  }
  for (const v1::LayerExclusion& exclusion : message.exclusions()) {
    spec.exclusions.push_back({.first = exclusion.first(),
                               .second = exclusion.second(),
                               .distance = exclusion.distance()});
  }
  return spec;
}

StatusOr<World> WorldFromMessage(const v1::World& message, const RasterCatalog* rasters) {
  StatusOr<WorldSpec> spec = WorldSpecFromMessage(message, rasters);
  if (!spec.ok()) return spec.status();
  return World::Create(*spec);
}

v1::World WorldToMessage(const World& world, const RasterCatalog* rasters) {
  v1::World message = WorldToMessage(world.spec());
  if (const RadiusField* field = world.radius_field()) {
    *message.mutable_radius_field() =
        RadiusFieldToMessage(field->spec(), RasterOf(field->spec(), rasters));
  }
  if (const WorldLayers* layers = world.layers()) {
    // Each layer's field by its raster's name; every pair's distance, defaults included, so a
    // client learns D without the default rule.
    message.clear_exclusions();
    for (int k = 0; k < layers->count(); ++k) {
      const RadiusField* field = layers->world(k).radius_field();
      v1::Layer& layer = *message.mutable_layers(k);
      if (field != nullptr && field->spec().kind != RadiusFieldKind::kConstant) {
        *layer.mutable_radius_field() =
            RadiusFieldToMessage(field->spec(), RasterOf(field->spec(), rasters));
      }
      for (int b = k + 1; b < layers->count(); ++b) {
        v1::LayerExclusion& exclusion = *message.add_exclusions();
        exclusion.set_first(layers->name(k));
        exclusion.set_second(layers->name(b));
        exclusion.set_distance(layers->exclusion(k, b));
      }
    }
  }
  return message;
}

v1::World WorldToMessage(const WorldSpec& spec) {
  v1::World message;
  message.set_seed(spec.seed);
  message.set_min_distance(spec.min_distance);
  switch (spec.algorithm) {
    case WorldAlgorithm::kA1:
      message.set_algorithm(v1::ALGORITHM_A1);
      break;
    case WorldAlgorithm::kA2:
      message.set_algorithm(v1::ALGORITHM_A2);
      break;
    case WorldAlgorithm::kA3:
      message.set_algorithm(v1::ALGORITHM_A3);
      break;
  }
  message.set_density(spec.density);
  message.set_generator_version(spec.generator_version);
  if (spec.radius_field.has_value() && spec.radius_field->kind != RadiusFieldKind::kConstant) {
    *message.mutable_radius_field() = RadiusFieldToMessage(*spec.radius_field, nullptr);
  }
  for (const LayerSpec& layer : spec.layers) {
    v1::Layer& out = *message.add_layers();
    out.set_name(layer.name);
    out.set_min_distance(layer.min_distance);
    if (layer.radius_field.has_value() && layer.radius_field->kind != RadiusFieldKind::kConstant) {
      *out.mutable_radius_field() = RadiusFieldToMessage(*layer.radius_field, nullptr);
    }
  }
  for (const LayerExclusionSpec& exclusion : spec.exclusions) {
    v1::LayerExclusion& out = *message.add_exclusions();
    out.set_first(exclusion.first);
    out.set_second(exclusion.second);
    out.set_distance(exclusion.distance);
  }
  return message;
}

Rect RectFromMessage(const v1::Rect& message) {
  return {message.x0(), message.y0(), message.x1(), message.y1()};
}

v1::Rect RectToMessage(const Rect& rect) {
  v1::Rect message;
  message.set_x0(rect.x0);
  message.set_y0(rect.y0);
  message.set_x1(rect.x1);
  message.set_y1(rect.y1);
  return message;
}

void AppendPoints(const PlanePoints& points, size_t begin, size_t end, v1::Points& message,
                  const RadiusField* field) {
  PointsAppender appender(message, end - begin, field);
  for (size_t k = begin; k < end; ++k) appender.Append(points.positions[k], points.ids[k]);
}

bool LayeredPointsCarryRadii(const World& world) {
  const WorldLayers* layers = world.layers();
  if (layers == nullptr) return false;
  for (const LayerSpec& layer : world.spec().layers) {
    // The spec's, not the layer world's: a later layer's world has a constant field.
    if (layer.radius_field.has_value()) return true;
  }
  return false;
}

PointsAppender::PointsAppender(v1::Points& message, size_t capacity, const RadiusField* field)
    : message_(message), start_(message.ids_size()), field_(field) {
  Reserve(capacity, field_ != nullptr, false);
}

PointsAppender::PointsAppender(v1::Points& message, size_t capacity, const World& world)
    : message_(message), start_(message.ids_size()), field_(world.radius_field()) {
  if (world.layers() != nullptr) {
    world_ = &world;
    layer_world_ = &world.layers()->world(0);
  }
  Reserve(capacity, field_ != nullptr || (world_ != nullptr && LayeredPointsCarryRadii(world)),
          world_ != nullptr);
}

void PointsAppender::Reserve(size_t capacity, bool radii, bool layers) {
  const int room = static_cast<int>(capacity);
  message_.mutable_xs()->Reserve(start_ + room);
  message_.mutable_ys()->Reserve(start_ + room);
  message_.mutable_ids()->Reserve(start_ + room);
  xs_ = message_.mutable_xs()->AddNAlreadyReserved(room);
  ys_ = message_.mutable_ys()->AddNAlreadyReserved(room);
  ids_ = message_.mutable_ids()->AddNAlreadyReserved(room);
  if (radii) {
    message_.mutable_radii()->Reserve(start_ + room);
    radii_ = message_.mutable_radii()->AddNAlreadyReserved(room);
  }
  if (layers) {
    message_.mutable_layers()->Reserve(start_ + room);
    layers_ = message_.mutable_layers()->AddNAlreadyReserved(room);
  }
}

void PointsAppender::StartLayer(int layer) {
  if (layer < 0) return;
  layer_ = static_cast<uint32_t>(layer);
  layer_world_ = &world_->layers()->world(layer);
}

PointsAppender::~PointsAppender() {
  const int size = start_ + static_cast<int>(count_);
  message_.mutable_xs()->Truncate(size);
  message_.mutable_ys()->Truncate(size);
  message_.mutable_ids()->Truncate(size);
  if (radii_ != nullptr) message_.mutable_radii()->Truncate(size);
  if (layers_ != nullptr) message_.mutable_layers()->Truncate(size);
}

namespace {

// Points.encoded, decoded; radii as long as the points decoded.
Status ReadEncoded(const v1::Points& message, PlanePoints& points, std::vector<double>* radii) {
  if (message.xs_size() != 0 || message.ys_size() != 0 || message.ids_size() != 0 ||
      message.layers_size() != 0) {
    return InvalidArgument("points: encoded and the packed xs, ys, ids, layers are both set");
  }
  const size_t before = points.ids.size();
  if (Status status = ReadEncodedPoints(message.encoded(), points); !status.ok()) return status;
  const size_t count = points.ids.size() - before;
  if (message.radii_size() != 0 && static_cast<size_t>(message.radii_size()) != count) {
    points.positions.resize(before);
    points.ids.resize(before);
    points.layers.resize(std::min(points.layers.size(), before));
    return InvalidArgument("points: radii must be empty or one per encoded point");
  }
  if (radii != nullptr) radii->insert(radii->end(), message.radii().begin(), message.radii().end());
  return Status::Ok();
}

}  // namespace

Status ReadPoints(const v1::Points& message, PlanePoints& points, std::vector<double>* radii) {
  if (message.has_encoded()) return ReadEncoded(message, points, radii);
  if (message.xs_size() != message.ys_size() || message.xs_size() != message.ids_size()) {
    return InvalidArgument("points: xs, ys and ids must have the same length");
  }
  if (message.radii_size() != 0 && message.radii_size() != message.xs_size()) {
    return InvalidArgument("points: radii must be empty or as long as xs");
  }
  if (message.layers_size() != 0 && message.layers_size() != message.xs_size()) {
    return InvalidArgument("points: layers must be empty or as long as xs");
  }
  for (const uint32_t layer : message.layers()) {
    if (layer > 255) return InvalidArgument("points: layers must be below 256");
  }
  if (radii != nullptr) radii->insert(radii->end(), message.radii().begin(), message.radii().end());
  for (int k = 0; k < message.xs_size(); ++k) {
    points.positions.push_back({message.xs(k), message.ys(k)});
    points.ids.push_back(message.ids(k));
  }
  points.layers.insert(points.layers.end(), message.layers().begin(), message.layers().end());
  return Status::Ok();
}

}  // namespace scallop
