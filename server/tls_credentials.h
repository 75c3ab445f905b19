// The listening port's credentials: plaintext, TLS, or mutual TLS, from the
// PEM files the configuration names, checked before the server starts so a
// bad file stops scallopd with a message instead of a silent handshake error.
#pragma once

#include <grpcpp/security/server_credentials.h>

#include <memory>

#include "scallop/base/status.h"
#include "server/server_config.h"

namespace scallop::server {

// Insecure credentials when tls_cert is empty. Otherwise TLS with tls_cert
// (a chain, leaf first) and tls_key; with tls_client_ca, clients must present
// a certificate that CA signs (GRPC_SSL_REQUEST_AND_REQUIRE_CLIENT_CERTIFICATE_AND_VERIFY).
// INVALID_ARGUMENT naming the setting and file when one is missing,
// unreadable or not PEM, or when the key does not belong to the certificate.
// Cost: reads and parses the files once, at start.
StatusOr<std::shared_ptr<grpc::ServerCredentials>> MakeServerCredentials(
    const ServerConfig& config);

}  // namespace scallop::server
