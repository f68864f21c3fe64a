#include <gtest/gtest.h>

#include <string>

#include "core/common/error.h"

namespace meshd {
namespace {

TEST(QuoteInput, ShortPrintableTextIsQuotedAsIs) {
  EXPECT_EQ(quote_input("j0000000001-9bca4c"), "'j0000000001-9bca4c'");
  EXPECT_EQ(quote_input(""), "''");
}

TEST(QuoteInput, BytesThatAreNotPrintableAreEscaped) {
  EXPECT_EQ(quote_input(std::string("a\nb\0c\\", 6)), "'a\\x0ab\\x00c\\x5c'");
  EXPECT_EQ(quote_input("\xff"), "'\\xff'");
}

TEST(QuoteInput, LongTextIsCutAndItsLengthSaid) {
  const std::string quoted = quote_input(std::string(100'000, 'x'));
  EXPECT_EQ(quoted, "'" + std::string(64, 'x') + "' (the first 64 of 100000 characters)");
  EXPECT_EQ(quote_input(std::string(64, 'y')), "'" + std::string(64, 'y') + "'");
}

}  // namespace
}  // namespace meshd
