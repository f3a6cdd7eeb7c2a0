/*
 * dnsr.h next to a user's own common names: the header declares only Dnsr* / DNSR_* / dnsr_* names, so a
 * translation unit that already defines Coord, TILE, MIN, MAX, Settings, Context, Result ... still compiles
 * (with -Wall -Wextra -Werror -pedantic: a redefined macro is an error). dnsr 0.1.0 leaked `typedef int32_t
 * Coord[2]`, `#define TILE` and `#define MOMENT_RADIUS` and failed here.
 */
#define TILE 16
#define MIN(a, b) ((a) < (b) ? (a) : (b))
#define MAX(a, b) ((a) > (b) ? (a) : (b))
#define MOMENT_RADIUS 3
#define MAX_FILTER_PASSES 2
typedef struct Coord { float u, v; } Coord;
typedef struct Settings { int quality; } Settings;
typedef struct Context { int id; } Context;
typedef enum Result { RESULT_OK } Result;
typedef int Error;
struct Rect { int left, top; };

#include "dnsr.h"

int main(void)
{
    Coord c = {1.0f, 2.0f};
    Settings s = {MIN(TILE, MAX(MOMENT_RADIUS, MAX_FILTER_PASSES))};
    Context ctx = {0};
    Result r = RESULT_OK;
    Error e = 0;
    struct Rect rect = {0, 0};
    DnsrSettings settings = {0};
    settings.sType = DNSR_STRUCTURE_TYPE_SETTINGS;
    int sum = (int)c.u + s.quality + ctx.id + (int)r + e + rect.left + (int)settings.filterPasses;
    return sum == 1 + 3 ? 0 : 1;
}
