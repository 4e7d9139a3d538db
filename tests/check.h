/* tests/check.h - test helper: checks that say what they saw. CHECK(cond, fmt, ...) prints its message and
 * fails the cmocka test; NEAR(a, b, tol) is |a - b| <= tol, printing both (cmocka 1.1.5 has no
 * assert_double_equal). Include after <cmocka.h> and <math.h>. */
#ifndef DASHPOT_TESTS_CHECK_H
#define DASHPOT_TESTS_CHECK_H

#define CHECK(cond, ...)                                                                                     \
    do {                                                                                                     \
        if (!(cond)) {                                                                                       \
            print_error(__VA_ARGS__);                                                                        \
            print_error("\n");                                                                               \
            fail_msg("check failed: %s", #cond);                                                            \
        }                                                                                                    \
    } while (0)

#define NEAR(a, b, tol)                                                                                      \
    do {                                                                                                     \
        double a_ = (a), b_ = (b);                                                                           \
        CHECK(fabs(a_ - b_) <= (tol), "%s = %.17g, expected %s = %.17g within %g", #a, a_, #b, b_,          \
              (double)(tol));                                                                                \
    } while (0)

#endif
