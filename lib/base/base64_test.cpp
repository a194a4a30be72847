#include "base64.hpp"
#include "../test_support/base64.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace dqskin {
namespace {

std::vector<uint8_t> bytes_of(const std::string& text) { return {text.begin(), text.end()}; }

// RFC 4648 section 10.
TEST(Base64, MatchesTheRfcTestVectors) {
  const std::pair<const char*, const char*> vectors[] = {
      {"", ""},         {"f", "Zg=="},         {"fo", "Zm8="},        {"foo", "Zm9v"},
      {"foob", "Zm9vYg=="}, {"fooba", "Zm9vYmE="}, {"foobar", "Zm9vYmFy"},
  };
  for (const auto& [plain, encoded] : vectors) {
    EXPECT_EQ(io::base64(bytes_of(plain)), encoded) << plain;
    std::vector<uint8_t> decoded;
    EXPECT_TRUE(testing_support::base64_decode(encoded, decoded)) << encoded;
    EXPECT_EQ(decoded, bytes_of(plain)) << encoded;
  }
}

TEST(Base64, UsesTheLastTwoCharactersOfTheAlphabetAndRoundTripsEveryByte) {
  EXPECT_EQ(io::base64(std::vector<uint8_t>{0xFB, 0xFF, 0xBF}), "+/+/");
  std::vector<uint8_t> all(256);
  for (size_t i = 0; i < all.size(); ++i) all[i] = uint8_t(i);
  for (size_t n = 0; n <= all.size(); n += 37) {
    const std::vector<uint8_t> part(all.begin(), all.begin() + std::ptrdiff_t(n));
    std::vector<uint8_t> back;
    ASSERT_TRUE(testing_support::base64_decode(io::base64(part), back));
    EXPECT_EQ(back, part) << n << " bytes";
  }
}

TEST(Base64, DecoderRejectsWhatIsNotPaddedBase64) {
  std::vector<uint8_t> bytes;
  EXPECT_FALSE(testing_support::base64_decode("Zg=", bytes));   // not a multiple of 4
  EXPECT_FALSE(testing_support::base64_decode("Zg*=", bytes));  // outside the alphabet
  EXPECT_FALSE(testing_support::base64_decode("Z=g=", bytes));  // padding in the middle
}

}  // namespace
}  // namespace dqskin
