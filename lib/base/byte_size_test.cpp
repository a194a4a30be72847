#include "byte_size.hpp"
#include "dqskin/error.hpp"

#include <gtest/gtest.h>

namespace {

using dqskin::byte_size;
using dqskin::parse_byte_size;

TEST(ByteSize, PrintsThreeSignificantDigitsInBinaryUnits) {
  EXPECT_EQ(byte_size(0), "0 bytes");
  EXPECT_EQ(byte_size(1), "1 byte");
  EXPECT_EQ(byte_size(1023), "1023 bytes");
  EXPECT_EQ(byte_size(1024), "1.00 KiB");
  EXPECT_EQ(byte_size(uint64_t(2) << 30), "2.00 GiB");
  EXPECT_EQ(byte_size(uint64_t(512) << 20), "512 MiB");
  EXPECT_EQ(byte_size(uint64_t(15) << 29), "7.50 GiB");
  EXPECT_EQ(byte_size(UINT64_MAX), "16.0 EiB");
}

TEST(ByteSize, ParsesPlainNumbersAndBinarySuffixes) {
  EXPECT_EQ(parse_byte_size("1073741824", "--max-memory"), uint64_t(1) << 30);
  EXPECT_EQ(parse_byte_size("4G", "--max-memory"), uint64_t(4) << 30);
  EXPECT_EQ(parse_byte_size("4gib", "--max-memory"), uint64_t(4) << 30);
  EXPECT_EQ(parse_byte_size("512M", "--max-memory"), uint64_t(512) << 20);
  EXPECT_EQ(parse_byte_size("64kB", "--max-memory"), uint64_t(64) << 10);
  EXPECT_EQ(parse_byte_size("1.5G", "--max-memory"), uint64_t(3) << 29);
  EXPECT_EQ(parse_byte_size("2T", "--max-memory"), uint64_t(2) << 40);
}

TEST(ByteSize, RefusesWhatIsNotASize) {
  for (const char* bad : {"", "G", "-1", "0", "0.1", "4X", "4 G", "nan", "inf", "1e30", "4GG", "-5M", "1e19"})
    EXPECT_THROW(parse_byte_size(bad, "--max-memory"), dqskin::InputError) << bad;
  try {
    parse_byte_size("lots", "--max-memory");
  } catch (const dqskin::InputError& e) {
    EXPECT_STREQ(e.what(), "--max-memory 'lots' is not a size in bytes (e.g. 2G, 512M, 1073741824)");
  }
}

}  // namespace
