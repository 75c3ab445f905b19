// Counts a world's points in a rectangle with the installed core, and makes
// a client (no call) to show the client library links: "count=N".
#include <cstdlib>
#include <iostream>

#include "scallop/plane/plane_engine.h"
#include "scallop_client.h"

int main(int argc, char** argv) {
  if (argc != 6) {
    std::cerr << "usage: count_points SEED X0 Y0 X1 Y1\n";
    return 2;
  }
  scallop::PlaneEngine engine({.threads = 1});
  // Every seed makes a valid world; World::Create is how any other spec is checked.
  const scallop::StatusOr<scallop::World> world =
      scallop::World::Create({.seed = std::strtoull(argv[1], nullptr, 10)});
  if (!world.ok()) {
    std::cerr << world.status().message() << '\n';
    return 2;
  }
  const scallop::Rect rect{std::atof(argv[2]), std::atof(argv[3]), std::atof(argv[4]),
                           std::atof(argv[5])};
  const scallop::StatusOr<int64_t> count = engine.Count(*world, rect);
  if (!count.ok()) {
    std::cerr << count.status().message() << '\n';
    return 1;
  }
  const scallop::client::ScallopClient client =
      scallop::client::ScallopClient::Connect("127.0.0.1:1");
  std::cout << "count=" << *count << (client.channel() ? "" : " (no channel)") << '\n';
  return 0;
}
