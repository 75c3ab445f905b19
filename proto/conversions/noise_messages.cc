// The noise channel table, read in both directions.
#include "noise_messages.h"

#include <array>
#include <utility>

namespace scallop {
namespace {

constexpr std::array<std::pair<NoiseChannel, v1::NoiseChannel>, 5> kChannels{{
    {NoiseChannel::kF1, v1::NOISE_CHANNEL_F1},
    {NoiseChannel::kF2, v1::NOISE_CHANNEL_F2},
    {NoiseChannel::kF2MinusF1, v1::NOISE_CHANNEL_F2_MINUS_F1},
    {NoiseChannel::kId, v1::NOISE_CHANNEL_ID},
    {NoiseChannel::kCellValue, v1::NOISE_CHANNEL_CELL_VALUE},
}};

}  // namespace

v1::NoiseChannel NoiseChannelToMessage(NoiseChannel channel) {
  for (const auto& [core, message] : kChannels) {
    if (core == channel) return message;
  }
  return v1::NOISE_CHANNEL_UNSPECIFIED;
}

std::optional<NoiseChannel> NoiseChannelFromMessage(v1::NoiseChannel channel) {
  for (const auto& [core, message] : kChannels) {
    if (message == channel) return core;
  }
  return std::nullopt;
}

}  // namespace scallop
