/*
 * runtime/base/numfmt.c: every number printed reads back as the same double,
 * and no shorter %g does (checked here by trying every shorter
 * precision); the 0.05 prints as 0.05.
 */
#include "../unit/check.h"
#include "base/numfmt.h"

#include <float.h>
#include <stdlib.h>
#include <string.h>

/* Reads back, and is the shortest that does. */
static int
shortest_ok(double x, char *got)
{
    num_shortest(got, x);
    if (strtod(got, NULL) != x && !(isnan(x) && isnan(strtod(got, NULL))))
        return 0;
    char b[64];
    for (int prec = 1; prec <= 17; prec++) { /* no %g that reads back is shorter */
        snprintf(b, sizeof b, "%.*g", prec, x);
        if (strtod(b, NULL) == x && strlen(b) < strlen(got))
            return 0;
    }
    return 1;
}

int
main(void)
{
    char got[NUM_MAX];
    CHECK(!strcmp(num_shortest(got, 0.05), "0.05"), "0.05 prints as %s", got);
    CHECK(!strcmp(num_shortest(got, 0.1 + 0.2), "0.30000000000000004"),
          "0.1 + 0.2 prints as %s (17 digits when it takes them)", got);
    CHECK(!strcmp(num_shortest(got, 9.81), "9.81") && !strcmp(num_shortest(got, 1.0), "1") &&
          !strcmp(num_shortest(got, 10.0), "10") && !strcmp(num_shortest(got, 1500.0), "1500"),
          "9.81, 1, 10 and 1500 as written (not 1e+01)");
    CHECK(!strcmp(num_shortest(got, -0.0), "0") && !strcmp(num_shortest(got, 0.0), "0") &&
              !strcmp(num_shortest(got, -1e-300), "-1e-300"),
          "-0 prints as %s, as 0 does (a sign on a zero puzzles: x'' -0); -1e-300 keeps its", got);
    double special[] = {1.0 / 3, -2.0 / 3, 1e-300, 4.9406564584124654e-324, DBL_MAX,
                        -DBL_MIN, 123456789012345678.0, 0.0, -0.0, 1e21, 1e-7};
    int ok = 1;
    for (size_t k = 0; k < sizeof special / sizeof special[0]; k++)
        ok &= shortest_ok(special[k], got);
    CHECK(ok, "extremes (denormals, DBL_MAX, -0, 1/3): read back, and nothing shorter does");
    ok = 1;
    for (int k = 0; k < 100000 && ok; k++) {
        double x = check_rand(-1, 1) * pow(10, (int)check_rand(-30, 30));
        ok &= shortest_ok(x, got);
    }
    CHECK(ok, "100000 random numbers: read back, and nothing shorter does");
    return check_done();
}
