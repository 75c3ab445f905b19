// Registration of the connection options, and reading the files they name.
#include "client/options/connection_options.h"

#include <CLI/CLI.hpp>
#include <fstream>
#include <sstream>

namespace scallop::cli {
namespace {

// The whole file, or INVALID_ARGUMENT naming the flag and the path. A PEM
// file must hold a block of the `pem` kind ("CERTIFICATE", "PRIVATE KEY"):
// a wrong file named by mistake is caught here, not as an opaque handshake
// failure (UNAVAILABLE) on the first call.
StatusOr<std::string> ReadFlagFile(const char* flag, const std::string& path,
                                   const char* pem = nullptr) {
  std::ifstream file(path, std::ios::binary);
  if (!file) return InvalidArgument(std::string(flag) + ": cannot read '" + path + "'");
  std::ostringstream text;
  text << file.rdbuf();
  if (file.bad()) return InvalidArgument(std::string(flag) + ": cannot read '" + path + "'");
  if (pem != nullptr && text.str().find(pem) == std::string::npos) {
    return InvalidArgument(std::string(flag) + ": '" + path + "' holds no PEM " + pem);
  }
  return text.str();
}

}  // namespace

void AddConnectionOptions(CLI::App& command, ConnectionArguments& arguments) {
  command.add_option("--tls-ca", arguments.tls_ca,
                     "PEM roots that sign the server's certificate (turns TLS on)");
  CLI::Option* cert = command.add_option("--tls-cert", arguments.tls_cert,
                                         "PEM client certificate, for mutual TLS (turns TLS on)");
  CLI::Option* key =
      command.add_option("--tls-key", arguments.tls_key, "PEM private key of --tls-cert");
  cert->needs(key);
  key->needs(cert);
  command.add_flag("--tls", arguments.tls, "TLS with the system's roots");
  // No `excludes`: SCALLOP_TOKEN in the environment counts as --token, and a
  // --token-file given for one command should win over it, not clash.
  command.add_option("--token-file", arguments.token_file,
                     "File whose first line is the bearer token (wins over --token)");
  command.add_option("--token", arguments.token, "Bearer token (better: SCALLOP_TOKEN)")
      ->envname("SCALLOP_TOKEN");
}

StatusOr<client::ConnectionOptions> ReadConnectionOptions(const ConnectionArguments& arguments) {
  client::ConnectionOptions options;
  options.tls = arguments.tls || !arguments.tls_ca.empty() || !arguments.tls_cert.empty();
  struct PemFile {
    const char* flag;
    const std::string& path;
    const char* kind;
    std::string& pem;
  };
  for (const PemFile& file :
       {PemFile{"--tls-ca", arguments.tls_ca, "CERTIFICATE", options.tls_ca_pem},
        PemFile{"--tls-cert", arguments.tls_cert, "CERTIFICATE", options.tls_cert_pem},
        PemFile{"--tls-key", arguments.tls_key, "PRIVATE KEY", options.tls_key_pem}}) {
    if (file.path.empty()) continue;
    StatusOr<std::string> text = ReadFlagFile(file.flag, file.path, file.kind);
    if (!text.ok()) return text.status();
    file.pem = std::move(*text);
  }
  options.token = arguments.token;
  if (!arguments.token_file.empty()) {
    StatusOr<std::string> text = ReadFlagFile("--token-file", arguments.token_file);
    if (!text.ok()) return text.status();
    std::istringstream lines(*text);
    std::getline(lines, options.token);
    if (!options.token.empty() && options.token.back() == '\r') options.token.pop_back();
    if (options.token.empty()) {
      return InvalidArgument("--token-file: '" + arguments.token_file +
                             "' has no token on its first line");
    }
  }
  return options;
}

StatusOr<client::ScallopClient> ConnectTo(const std::string& server,
                                          const ConnectionArguments& arguments) {
  StatusOr<client::ConnectionOptions> options = ReadConnectionOptions(arguments);
  if (!options.ok()) return options.status();
  return client::ScallopClient::Connect(server, *options);
}

}  // namespace scallop::cli
