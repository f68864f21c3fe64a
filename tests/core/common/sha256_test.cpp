#include "core/common/sha256.h"

#include <gtest/gtest.h>

#include <string>

namespace meshd {
namespace {

// FIPS 180-2's examples.
TEST(Sha256, KnownDigests) {
  EXPECT_EQ(sha256_hex(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  EXPECT_EQ(sha256_hex("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(sha256_hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
            "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
}

TEST(Sha256, PiecesHashAsTheWhole) {
  std::string whole;
  for (int i = 0; i < 100'000; ++i) whole.push_back(static_cast<char>(i * 7919 % 251));
  Sha256 pieces;
  for (size_t offset = 0; offset < whole.size(); offset += 4'099)
    pieces.update(std::string_view(whole).substr(offset, 4'099));
  EXPECT_EQ(pieces.hex(), sha256_hex(whole));
}

TEST(Sha256, ADigestMidwayLeavesTheRunningOneGoingOn) {
  Sha256 sha;
  sha.update("ab");
  EXPECT_EQ(sha.hex(), sha256_hex("ab"));
  sha.update("c");
  EXPECT_EQ(sha.hex(), sha256_hex("abc"));
}

}  // namespace
}  // namespace meshd
