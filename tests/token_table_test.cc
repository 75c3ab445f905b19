// The token file's format and the lookup: each token finds its own grant, and
// nothing else (prefixes, extensions, case changes) finds any; every
// malformed file is refused with the file and line named.
#include "server/token_table.h"

#include <gtest/gtest.h>

namespace scallop::server {
namespace {

const std::set<std::string> kWorlds{"coast", "dense", "default"};

TEST(TokenTableTest, FindsEachTokensGrantAndNothingNearIt) {
  StatusOr<TokenTable> table = TokenTable::Parse(
      "# operators\n"
      "operator-token-0123456789\n"
      "\n"
      "   # coast team, two worlds\n"
      "coast-token-0123456789\tcoast,dense\r\n",
      "tokens", kWorlds);
  ASSERT_TRUE(table.ok()) << table.status().message();
  EXPECT_EQ(table->size(), 2u);
  const TokenGrant* all = table->Find("operator-token-0123456789");
  ASSERT_NE(all, nullptr);
  EXPECT_TRUE(all->worlds.empty());
  const TokenGrant* coast = table->Find("coast-token-0123456789");
  ASSERT_NE(coast, nullptr);
  EXPECT_EQ(coast->worlds, (std::set<std::string>{"coast", "dense"}));
  for (const char* near : {"operator-token-012345678", "operator-token-01234567890",
                           "OPERATOR-token-0123456789", "", "# operators"}) {
    EXPECT_EQ(table->Find(near), nullptr) << near;
  }
}

TEST(TokenTableTest, RefusesMalformedFilesNamingTheLine) {
  const std::pair<const char*, const char*> cases[] = {
      {"short\n", "tokens:1: a token must be 16 to 512 characters, got 5"},
      {"ok-token-0123456789\nok-token-0123456789\n", "tokens:2: token repeated"},
      {"ok-token-0123456789 coast extra\n", "tokens:1: expected TOKEN [WORLD,WORLD...]"},
      {"ok-token-0123456789 coast,nowhere\n", "tokens:1: no configured world named 'nowhere'"},
      {"ok-token-0123456789 coast,,dense\n", "tokens:1: no configured world named ''"},
      {"# only a comment\n\n", "tokens: holds no token"},
      {"ok-token-0123456789\xff\n", "tokens:1: a token must be printable ASCII"},
  };
  for (const auto& [text, message] : cases) {
    StatusOr<TokenTable> table = TokenTable::Parse(text, "tokens", kWorlds);
    ASSERT_FALSE(table.ok()) << text;
    EXPECT_NE(table.status().message().find(message), std::string::npos)
        << table.status().message();
    EXPECT_EQ(table.status().message().rfind("auth_tokens: ", 0), 0u);
  }
}

TEST(TokenTableTest, AnUnreadableFileIsNamed) {
  StatusOr<TokenTable> table = TokenTable::Load("/nonexistent/tokens", kWorlds);
  ASSERT_FALSE(table.ok());
  EXPECT_EQ(table.status().message(), "auth_tokens: cannot read '/nonexistent/tokens'");
}

}  // namespace
}  // namespace scallop::server
