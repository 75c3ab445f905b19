// A world as YAML: the schema of a named world in scallopd's config (`worlds: {NAME: ...}`),
// read by the config and by `scallop --world-file`. Keys: seed, min_distance, algorithm, density,
// radius_field ({noise: {...}} or {raster: {raster_name, ...}}, the message's field names), and
// for a layered world layers ([{name, min_distance | radius_field}]) and exclusions
// ([{first, second, distance}]). Unknown keys are refused, so that a typo is not ignored.
#pragma once

#include <yaml-cpp/yaml.h>

#include <set>
#include <string>
#include <vector>

#include "raster_catalog.h"
#include "scallop/base/status.h"
#include "scallop/plane/world.h"
#include "scallop/v1/scallop.pb.h"

namespace scallop {

// INVALID_ARGUMENT naming `where`: KEY for the first key of `node` not in `known`, or when `node`
// is not a map.
Status CheckYamlKeys(const YAML::Node& node, const std::set<std::string>& known,
                     const std::string& where);

// The world `node` describes as the message a request carries, each raster_name as it is given
// (a server's raster names, which it judges), its values unchecked but for the keys (unknown
// ones named `where`.KEY, `where`.layers[1].KEY...), the algorithm's name (`where`.algorithm)
// and the shapes of lists and maps. Missing keys take the config's defaults (min_distance 1,
// algorithm a3, density 2). For a client that sends a YAML world to scallopd. May throw
// YAML::Exception for a value of the wrong type.
StatusOr<v1::World> WorldMessageFromYaml(const YAML::Node& node, const std::string& where);

// The world `node` describes (WorldMessageFromYaml, then read as a request's world would be),
// its rasters named in `rasters`. Errors are INVALID_ARGUMENT led by
// `where` ("config.yaml: worlds.coast"): a key unknown, a field's value (`where`.radius_field.noise
// .frequency, `where`.layers[1].radius_field...), or World::Create's message after `where`: ".
// May throw YAML::Exception for a value of the wrong type (the caller names the file).
StatusOr<World> WorldFromYaml(const YAML::Node& node, const RasterCatalog& rasters,
                              const std::string& where);

// Every raster_name the world's fields give (its own and its layers'), in order, for a reader
// that loads rasters by path (`scallop --world-file`).
std::vector<std::string> RasterNamesInYaml(const YAML::Node& node);

}  // namespace scallop
