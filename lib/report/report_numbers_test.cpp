// The page's number rule (report_numbers.hpp), which report_check.mjs repeats in JavaScript.
#include "report_numbers.hpp"

#include <gtest/gtest.h>

namespace dqskin::report_detail {
namespace {

TEST(ReportNumbers, ShowsThreeSignificantDigits) {
  EXPECT_EQ(shown_number(0.012), "0.0120");
  EXPECT_EQ(shown_number(0.0123456789), "0.0123");
  EXPECT_EQ(shown_number(0.93), "0.930");
  EXPECT_EQ(shown_number(1.5), "1.50");
  EXPECT_EQ(shown_number(35.04), "35.0");
  EXPECT_EQ(shown_number(170.2), "170");
  EXPECT_EQ(shown_number(0.0001), "0.000100");
  EXPECT_EQ(shown_number(-0.5), "-0.500");
}

TEST(ReportNumbers, ShowsIntegersWithAllTheirDigits) {
  EXPECT_EQ(shown_number(0), "0");
  EXPECT_EQ(shown_number(-0.0), "0");
  EXPECT_EQ(shown_number(143), "143");
  EXPECT_EQ(shown_number(1047), "1047");
  EXPECT_EQ(shown_number(-12), "-12");
}

TEST(ReportNumbers, ShowsTinyAndHugeValuesInScientificNotationWithABareExponent) {
  EXPECT_EQ(shown_number(1.2345e-5), "1.23e-5");
  EXPECT_EQ(shown_number(-3e-7), "-3.00e-7");
  EXPECT_EQ(shown_number(4.5e15), "4.50e15");
}

// The rule the browser check repeats in JavaScript: decimals from the unrounded magnitude, and exact ties
// to even (JavaScript's toFixed rounds them away from zero; report_check.mjs corrects for that).
TEST(ReportNumbers, RoundsTiesToEvenOnTheDecimalsOfTheUnroundedMagnitude) {
  EXPECT_EQ(shown_number(1.125), "1.12");
  EXPECT_EQ(shown_number(1.375), "1.38");
  EXPECT_EQ(shown_number(170.5), "170");
  EXPECT_EQ(shown_number(171.5), "172");
  EXPECT_EQ(shown_number(0.09996), "0.1000");
}

TEST(ReportNumbers, WritesSvgCoordinatesWithOneDecimal) {
  EXPECT_EQ(svg_number(12.34), "12.3");
  EXPECT_EQ(svg_number(3.0), "3");
  EXPECT_EQ(svg_number(-0.04), "0");
  EXPECT_EQ(svg_number(-2.26), "-2.3");
}

}  // namespace
}  // namespace dqskin::report_detail
