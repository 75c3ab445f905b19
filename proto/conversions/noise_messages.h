// Conversions between the API's noise channel (scallop.v1.NoiseChannel) and
// the core's NoiseChannel, one table for both directions, shared by scallopd
// and the CLI.
#pragma once

#include <optional>

#include "scallop/noise/noise_grid.h"
#include "scallop/v1/scallop.pb.h"

namespace scallop {

v1::NoiseChannel NoiseChannelToMessage(NoiseChannel channel);

// Nullopt for NOISE_CHANNEL_UNSPECIFIED and values this build does not know.
std::optional<NoiseChannel> NoiseChannelFromMessage(v1::NoiseChannel channel);

}  // namespace scallop
