// What a call may cost, in the units of AdmissionBudget: the regions it may
// touch, an upper bound on its work (a cold region is generated once, a warm
// one copied). Computed before admission from the request alone, in O(1)
// (Nearest: one pass over its positions); a request the call will refuse as
// invalid costs 1, since its refusal costs nothing.
#pragma once

#include <cstdint>

#include "scallop/geometry/rect.h"
#include "scallop/plane/world.h"
#include "scallop/v1/scallop.pb.h"
#include "server/world_registry.h"

namespace scallop::server {

// Regions `rect` overlaps in `world`; 1 when the rectangle is out of bounds.
// A layered world: the sum over every layer of its own regions (whatever the
// request's filter, since a later layer's regions read the earlier ones').
int64_t RegionsCost(const World& world, const Rect& rect);

// GetPoints: its rectangle. Verify: the rectangle and its halo (2 d; a
// layered world's max(2 largest spacing, largest D)). Nearest and NoiseGrid
// of a layered world: the regions of the layer asked for, with the brute
// force's reach counted as for masks (exclusion disks leave spots farther
// from the layer's points than its spacing).
// NoiseGrid and Nearest: the regions of the box around their samples or
// positions, or their number, or `max_regions` (max_nearest_regions: a call
// whose points lie in more regions is refused before any work), the least;
// on a radius-field world with masks, where a position near a mask may need
// the brute force's 32 r_max square, the box grown by that or that square's
// regions per position (.cc).
int64_t RequestCost(const WorldRegistry& worlds, const v1::GetPointsRequest& request);
int64_t RequestCost(const WorldRegistry& worlds, const v1::VerifyRequest& request);
int64_t RequestCost(const WorldRegistry& worlds, const v1::NoiseGridRequest& request,
                    int64_t max_regions);
int64_t RequestCost(const WorldRegistry& worlds, const v1::NearestRequest& request,
                    int64_t max_regions);

}  // namespace scallop::server
