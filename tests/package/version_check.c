/*
 * tvo/version.h from a consumer's side (built by consumer/ through find_package and by
 * package_check.cmake through pkg-config): TVO_VERSION_STRING must be the version CMake was given
 * (EXPECT_VERSION, from firmware/cmake/tvo_version.cmake) and agree with the three numbers.
 */
#include <stdio.h>
#include <string.h>

#include "tvo/version.h"

#define VERSION_TEXT_(x) #x
#define VERSION_TEXT(x) VERSION_TEXT_(x)

int main(void)
{
    const char *joined = VERSION_TEXT(TVO_VERSION_MAJOR) "." VERSION_TEXT(TVO_VERSION_MINOR) "." VERSION_TEXT(
        TVO_VERSION_PATCH);
    if (strcmp(TVO_VERSION_STRING, EXPECT_VERSION) != 0 || strcmp(joined, EXPECT_VERSION) != 0) {
        fprintf(stderr, "tvo/version.h: TVO_VERSION_STRING \"%s\", numbers %s, CMake's version %s\n",
                TVO_VERSION_STRING, joined, EXPECT_VERSION);
        return 1;
    }
    printf("tvo/version.h: %s, as CMake's version\n", TVO_VERSION_STRING);
    return 0;
}
