// Parsing the token file, and the constant-time lookup over SHA-256 digests.
#include "server/token_table.h"

#include <openssl/crypto.h>
#include <openssl/sha.h>

#include <fstream>
#include <sstream>

namespace scallop::server {

TokenTable::Digest TokenTable::Hash(std::string_view token) {
  Digest digest;
  SHA256(reinterpret_cast<const unsigned char*>(token.data()), token.size(), digest.data());
  return digest;
}

StatusOr<TokenTable> TokenTable::Load(const std::string& path,
                                      const std::set<std::string>& known_worlds) {
  std::ifstream file(path, std::ios::binary);
  if (!file) return InvalidArgument("auth_tokens: cannot read '" + path + "'");
  std::ostringstream text;
  text << file.rdbuf();
  if (file.bad()) return InvalidArgument("auth_tokens: cannot read '" + path + "'");
  return Parse(text.str(), path, known_worlds);
}

StatusOr<TokenTable> TokenTable::Parse(std::string_view text, const std::string& path,
                                       const std::set<std::string>& known_worlds) {
  TokenTable table;
  std::istringstream lines{std::string(text)};
  int number = 0;
  for (std::string line; std::getline(lines, line);) {
    ++number;
    const std::string where = "auth_tokens: " + path + ":" + std::to_string(number) + ": ";
    std::istringstream fields(line);
    std::string token, worlds, extra;
    fields >> token >> worlds >> extra;
    if (token.empty() || token[0] == '#') continue;
    if (!extra.empty()) return InvalidArgument(where + "expected TOKEN [WORLD,WORLD...]");
    if (token.size() < 16 || token.size() > 512) {
      return InvalidArgument(where + "a token must be 16 to 512 characters, got " +
                             std::to_string(token.size()));
    }
    for (char c : token) {
      if (c < 0x21 || c > 0x7e) return InvalidArgument(where + "a token must be printable ASCII");
    }
    Entry entry{.digest = Hash(token), .grant = {}};
    std::istringstream names(worlds);
    for (std::string name; std::getline(names, name, ',');) {
      if (!known_worlds.contains(name)) {
        return InvalidArgument(where + "no configured world named '" + name + "'");
      }
      entry.grant.worlds.insert(name);
    }
    if (table.Find(token) != nullptr) return InvalidArgument(where + "token repeated");
    table.entries_.push_back(std::move(entry));
  }
  if (table.entries_.empty()) {
    return InvalidArgument("auth_tokens: " + path + ": holds no token (every call would fail)");
  }
  return table;
}

const TokenGrant* TokenTable::Find(std::string_view token) const {
  const Digest digest = Hash(token);
  const TokenGrant* found = nullptr;
  // No early exit: the time taken does not depend on which entry matches.
  for (const Entry& entry : entries_) {
    if (CRYPTO_memcmp(entry.digest.data(), digest.data(), digest.size()) == 0) {
      found = &entry.grant;
    }
  }
  return found;
}

}  // namespace scallop::server
