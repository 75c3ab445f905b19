// scallopd's configuration from arbitrary text: the YAML file (LoadConfigFile,
// through a real file) and the --world flag (AddWorldSpec, on the input's
// first line). Neither may crash or throw; an error names the file and key
// (or --world); a file that loads either passes ValidateConfig or fails it
// with a message naming the setting; every loaded world is valid.
#include <cstdint>
#include <string>

#include "fuzz/fuzz_check.h"
#include "fuzz/fuzz_input_file.h"
#include "server/server_config.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace scallop;
  using namespace scallop::server;
  const std::string text(reinterpret_cast<const char*>(data), size);

  ServerConfig flags;
  const Status spec = AddWorldSpec(text.substr(0, text.find('\n')), flags);
  SCALLOP_FUZZ_CHECK(spec.ok() || spec.message().starts_with("--world"),
                     "--world error without the flag's name: " + spec.message());

  const std::string& path = fuzz::WriteInputFile(data, size, ".yaml");
  ServerConfig config;
  const Status loaded = LoadConfigFile(path, config);
  if (!loaded.ok()) {
    SCALLOP_FUZZ_CHECK(loaded.message().starts_with(path + ": "),
                       "config error without the file's name: " + loaded.message());
    return 0;
  }
  for (const auto& [name, world] : config.worlds) {
    SCALLOP_FUZZ_CHECK(World::Create(world.spec()).ok(), "loaded an invalid world " + name);
  }
  const Status valid = ValidateConfig(config);
  SCALLOP_FUZZ_CHECK(valid.ok() || valid.message().find(": ") != std::string::npos,
                     "validation error without a setting's name: " + valid.message());
  return 0;
}
