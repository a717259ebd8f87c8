/*
 * runtime/step/events.c on functions whose roots are known:
 *  - ev_crossed: each direction, a landing on exactly 0, and a start at 0
 *    (an event that has just fired) that never counts;
 *  - ev_root: cos t in [1, 2] gives pi/2, t^3 - 2 in [0, 2] gives 2^(1/3),
 *    and a steep tanh(1000 (t - 0.3)), each to within 4 units of rounding
 *    of the root and in few evaluations (superlinear); the answer is never
 *    before the crossing (g there is 0 or past it); a good first guess
 *    saves evaluations; g failing (NAN) gives NAN.
 */
#include "../unit/check.h"
#include "step/events.h"

#include <float.h>
#include <math.h>

static const double PI = 3.14159265358979323846;

static double g_cos(void *ctx, double t) { (void)ctx; return cos(t); }
static double g_cube(void *ctx, double t) { (void)ctx; return t * t * t - 2; }
static double g_steep(void *ctx, double t) { (void)ctx; return tanh(1000 * (t - 0.3)); }
static double g_fails(void *ctx, double t) { (void)ctx; return t > 0.5 ? NAN : -1; }

static void
test_crossed(void)
{
    CHECK(ev_crossed(-1, 1, -1) && !ev_crossed(-1, -1, 1) && ev_crossed(1, -1, 1) &&
          !ev_crossed(1, 1, -1), "down fires from + to -, up from - to +, not the reverse");
    CHECK(ev_crossed(0, 1, -1) && ev_crossed(0, -1, 1), "both fires either way");
    CHECK(ev_crossed(-1, 1, 0) && ev_crossed(1, -1, 0), "landing on exactly 0 is a crossing");
    CHECK(!ev_crossed(0, 0, -1) && !ev_crossed(0, 0, 1) && !ev_crossed(-1, 0, -1),
          "a start at exactly 0 (an event that just fired) never is");
    CHECK(!ev_crossed(0, 1, 2) && !ev_crossed(0, NAN, -1) && !ev_crossed(0, 1, NAN),
          "no sign change, or NAN: no crossing");
}

/* |got - want| within `ulps` units of rounding of want */
static int
ulps_off(double got, double want, double *ulps)
{
    *ulps = fabs(got - want) / (DBL_EPSILON * fabs(want));
    return *ulps <= 4;
}

static void
test_root(void)
{
    int evals;
    double u;
    double t = ev_root(g_cos, NULL, 1, cos(1.0), 2, cos(2.0), NAN, &evals);
    CHECK(ulps_off(t, PI / 2, &u) && cos(t) <= 0 && evals <= 12,
          "cos t: pi/2 to %.1f ulps in %d evaluations, at or past the crossing", u, evals);
    t = ev_root(g_cube, NULL, 0, -2, 2, 6, NAN, &evals);
    CHECK(ulps_off(t, cbrt(2.0), &u) && g_cube(NULL, t) >= 0 && evals <= 20,
          "t^3 - 2: 2^(1/3) to %.1f ulps in %d evaluations", u, evals);
    t = ev_root(g_steep, NULL, 0, g_steep(NULL, 0), 1, g_steep(NULL, 1), NAN, &evals);
    CHECK(ulps_off(t, 0.3, &u) && evals < 100,
          "tanh(1000 (t - 0.3)): 0.3 to %.1f ulps in %d evaluations", u, evals);
    int guessed;
    ev_root(g_cos, NULL, 1, cos(1.0), 2, cos(2.0), 1.5707963, &guessed);
    CHECK(guessed < evals || guessed <= 6, "a first guess near the root: %d evaluations",
          guessed);
    t = ev_root(g_cos, NULL, 2, cos(2.0), 1, cos(1.0), NAN, &evals);
    CHECK(ulps_off(t, PI / 2, &u) && cos(t) >= 0,
          "a bracket given backwards (b < a) works the same (%.1f ulps)", u);
    t = ev_root(g_fails, NULL, 0, -1, 1, 1, NAN, &evals);
    CHECK(isnan(t), "g failing at a trial time gives NAN");
    t = ev_root(g_cos, NULL, 1, cos(1.0), PI / 2, 0, NAN, &evals);
    CHECK(t == PI / 2 && evals == 0, "g already 0 at the far end: that end, no evaluation");
}

int
main(void)
{
    test_crossed();
    test_root();
    return check_done();
}
