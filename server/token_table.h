// The bearer tokens scallopd accepts (--auth-tokens FILE), kept only as
// SHA-256 digests, each with the worlds it may use. A presented token is
// compared with every entry in constant time, so timing reveals no prefix.
#pragma once

#include <array>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "scallop/base/status.h"

namespace scallop::server {

// What a token allows. Thread-safe to read from many calls at once.
struct TokenGrant {
  // Empty: every world, named or inline. Otherwise only these configured
  // names; a request naming no world is asking for the default world's name,
  // and an inline world names none, so it is refused.
  std::set<std::string> worlds;
};

class TokenTable {
 public:
  // Reads the file: one token a line, optionally followed by whitespace and
  // a comma-separated list of world names ("TOKEN coast,dense"); blank lines
  // and lines whose first non-blank character is '#' are skipped. Tokens are
  // 16 to 512 printable ASCII characters without spaces (shorter ones are
  // guessable). INVALID_ARGUMENT naming the file and line when it cannot be
  // read, a line is malformed, a token repeats, a world is not in
  // `known_worlds`, or it holds no token. Cost: one SHA-256 a token.
  static StatusOr<TokenTable> Load(const std::string& path,
                                   const std::set<std::string>& known_worlds);
  // The same from the file's text; `path` only names it in messages.
  static StatusOr<TokenTable> Parse(std::string_view text, const std::string& path,
                                    const std::set<std::string>& known_worlds);

  // The grant of `token`, or null when it is not in the table. Cost: one
  // SHA-256 and a CRYPTO_memcmp against every entry, whatever matches.
  const TokenGrant* Find(std::string_view token) const;
  size_t size() const { return entries_.size(); }

 private:
  using Digest = std::array<unsigned char, 32>;
  struct Entry {
    Digest digest;
    TokenGrant grant;
  };
  static Digest Hash(std::string_view token);

  std::vector<Entry> entries_;
};

}  // namespace scallop::server
