// The options that say how the CLI reaches scallopd (--tls-ca, --tls-cert,
// --tls-key, --token-file, --token or SCALLOP_TOKEN), and the files they name
// read and checked into the client library's ConnectionOptions.
#pragma once

#include <string>

#include "client/options/cli_fwd.h"
#include "scallop/base/status.h"
#include "scallop_client.h"

namespace scallop::cli {

struct ConnectionArguments {
  std::string tls_ca;      // PEM file of the roots that sign the server; turns TLS on
  std::string tls_cert;    // PEM file of the client certificate (mutual TLS); turns TLS on
  std::string tls_key;     // PEM file of its private key
  bool tls = false;        // TLS with the system's roots
  std::string token_file;  // first line is the bearer token
  std::string token;       // the token itself, best from SCALLOP_TOKEN (not shell history)
};

// Adds the options above to `command`; --tls-cert and --tls-key need each other.
void AddConnectionOptions(CLI::App& command, ConnectionArguments& arguments);

// Reads the files. INVALID_ARGUMENT naming the flag and the file when one is
// missing, unreadable or not PEM, or when the token file holds no token.
StatusOr<client::ConnectionOptions> ReadConnectionOptions(const ConnectionArguments& arguments);

// A client of `server` as `arguments` say; the errors of ReadConnectionOptions.
StatusOr<client::ScallopClient> ConnectTo(const std::string& server,
                                          const ConnectionArguments& arguments);

}  // namespace scallop::cli
