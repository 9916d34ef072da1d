// Names the factor and checks a residual, never a Jacobian: the check must still fail.
#include "factors/unchecked_factor.h"

TEST(UncheckedFactor, ResidualOnly) { EXPECT_NE(UncheckedFactor::Create(), nullptr); }
