// The refinement oracles' scale-free quantities on hand-made corner values.
#include "radiosity/solver/oracle.h"

#include <gtest/gtest.h>

namespace dynrad::rad {
namespace {

OracleInputs inputs(double b0, double b1, double b2, double d0, double d1, double d2) {
  return OracleInputs{{Rgb(b0), Rgb(b1), Rgb(b2)}, {Rgb(d0), Rgb(d1), Rgb(d2)}};
}

TEST(Oracle, QuantitiesAreScaleFree) {
  const OracleInputs in = inputs(2, 1, 1, 1, 0.5, 0.5);
  EXPECT_DOUBLE_EQ(cumulated_gradient(in), 0.5);  // (2 - 1) / 2
  EXPECT_DOUBLE_EQ(current_gradient(in), 0.5);    // (1 - 0.5) / 1
  EXPECT_DOUBLE_EQ(current_ratio(in), 0.5);       // mean 2/3 over mean 4/3
  // The same picture a thousand times brighter gives the same numbers.
  const OracleInputs bright = inputs(2000, 1000, 1000, 1000, 500, 500);
  EXPECT_DOUBLE_EQ(cumulated_gradient(bright), cumulated_gradient(in));
  EXPECT_DOUBLE_EQ(current_ratio(bright), current_ratio(in));
  // Black stays black without dividing by zero.
  EXPECT_EQ(cumulated_gradient(inputs(0, 0, 0, 0, 0, 0)), 0.0);
  EXPECT_EQ(current_ratio(inputs(0, 0, 0, 0, 0, 0)), 0.0);
}

TEST(Oracle, DynamicNeedsAllThreeConditions) {
  OracleThresholds t;  // 0.25 each
  t.variant = OracleThresholds::Variant::paper;
  EXPECT_TRUE(dynamic_oracle(inputs(2, 1, 1, 1, 0.5, 0.5), t));
  // Uneven shading, but this sender lights the element evenly: no refinement for it.
  EXPECT_FALSE(dynamic_oracle(inputs(2, 1, 1, 0.5, 0.5, 0.5), t));
  // This sender is uneven but contributes little next to what is there already.
  EXPECT_FALSE(dynamic_oracle(inputs(20, 10, 10, 1, 0.5, 0.5), t));
  // Even shading: nothing to refine.
  EXPECT_FALSE(dynamic_oracle(inputs(1, 1, 1, 1, 0.5, 0.5), t));
  EXPECT_TRUE(adaptive_oracle(inputs(2, 1, 1, 0, 0, 0), 0.25));
  EXPECT_FALSE(adaptive_oracle(inputs(1.1, 1, 1, 0, 0, 0), 0.25));
}

TEST(Oracle, PushdownRefinesWhereInterpolationWouldBeWrong) {
  OracleThresholds t;  // the push-down oracle is the default
  t.pushdown = 0.1;
  t.pushdown_floor = 0;
  // A weak sender (a twentieth of the element's light) whose transfer bends: the
  // paper's share condition stops it, the push-down oracle does not.
  OracleInputs in = inputs(20, 10, 10, 1, 0.5, 0.5);
  in.current_peak = 1;
  in.pushdown_error = 0.3;  // 30% of this transfer's peak would be wrong
  EXPECT_DOUBLE_EQ(pushdown_gradient(in), 0.3);
  EXPECT_TRUE(dynamic_oracle(in, t));
  OracleThresholds paper;
  paper.variant = OracleThresholds::Variant::paper;
  EXPECT_FALSE(dynamic_oracle(in, paper));
  // With a floor, a transfer that small a share of B is measured against the floor.
  OracleThresholds floored = t;
  floored.pushdown_floor = 0.5;                             // errors against max(1, 0.5 * 20) = 10
  EXPECT_DOUBLE_EQ(pushdown_gradient(in, 0.5), 0.03);
  EXPECT_FALSE(dynamic_oracle(in, floored));
  // The same transfer, nearly linear across the element: push-down is good enough.
  in.pushdown_error = 0.05;
  EXPECT_FALSE(dynamic_oracle(in, t));
  // Scale-free: ten times brighter, same answer.
  OracleInputs bright = inputs(200, 100, 100, 10, 5, 5);
  bright.current_peak = 10;
  bright.pushdown_error = 3;
  EXPECT_DOUBLE_EQ(pushdown_gradient(bright), 0.3);
  // Even shading: nothing to refine, whatever the transfer does.
  OracleInputs even = inputs(1, 1, 1, 1, 0.5, 0.5);
  even.current_peak = 1;
  even.pushdown_error = 0.5;
  EXPECT_FALSE(dynamic_oracle(even, t));
  // A sender that does not reach the element.
  EXPECT_EQ(pushdown_gradient(inputs(2, 1, 1, 0, 0, 0)), 0.0);
}

}  // namespace
}  // namespace dynrad::rad
