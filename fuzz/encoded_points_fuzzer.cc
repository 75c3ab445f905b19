// The client library's decoder of compact points (docs/wire.md) on Points
// messages parsed from arbitrary bytes, as a malicious or broken server could
// send them: ReadPoints never crashes or reads out of bounds, refuses with a
// message naming the field ("points: ..." or "encoded...: ..."), leaves the
// points it was given as they were when it refuses, and otherwise appends as
// many ids as positions (and radii, if any, one a point).
#include <cstdint>
#include <string>
#include <vector>

#include "fuzz/fuzz_check.h"
#include "world_messages.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  scallop::v1::Points message;
  if (!message.ParseFromArray(data, static_cast<int>(size))) return 0;
  scallop::PlanePoints points;
  points.positions.push_back({1, 2});  // an earlier point, to stay untouched
  points.ids.push_back(42);
  std::vector<double> radii;
  const scallop::Status status = scallop::ReadPoints(message, points, &radii);
  if (!status.ok()) {
    const std::string& text = status.message();
    SCALLOP_FUZZ_CHECK(text.starts_with("points") || text.starts_with("encoded"),
                       "refusal without a field name: " + text);
    SCALLOP_FUZZ_CHECK(points.ids.size() == 1 && points.positions.size() == 1 && radii.empty(),
                       "a refused message changed the points: " + text);
    return 0;
  }
  SCALLOP_FUZZ_CHECK(points.ids.size() == points.positions.size(), "ids and positions differ");
  SCALLOP_FUZZ_CHECK(radii.empty() || radii.size() + 1 == points.ids.size(), "radii miscounted");
  SCALLOP_FUZZ_CHECK(points.ids[0] == 42, "an earlier point was changed");
  return 0;
}
