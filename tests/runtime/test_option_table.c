/*
 * runtime/front/option_table.c: every option of enum Option has a row, found
 * again by its name, and the row's value (what --help shows) agrees with
 * the enum's order (what parsing goes by: the options from FIRST_FLAG on
 * take no value).
 */
#include "../unit/check.h"
#include "front/option_table.h"

#include <string.h>

int
main(void)
{
    int rowless = 0, lost = 0, disagree = 0;
    for (int k = 0; k < NOPTIONS; k++) {
        const char *name = option_name(k);
        if (!strcmp(name, "?")) {
            rowless++;
            continue;
        }
        lost += option_find(name, strlen(name)) != k;
        disagree += option_takes_value(k) != (k < FIRST_FLAG);
    }
    CHECK(rowless == 0, "every one of the %d options has a row (%d without)", NOPTIONS, rowless);
    CHECK(lost == 0, "each option's name finds it again (%d do not)", lost);
    CHECK(disagree == 0, "an option takes a value in --help's row exactly when parsing "
          "reads one, before FIRST_FLAG (%d disagree)", disagree);
    CHECK(option_find("--no-such", 9) == -1 && option_takes_value(NOPTIONS) == -1,
          "an unknown name or option: -1");
    return check_done();
}
