/* src/json/stability_svg.c - a stability map as an SVG image a person can look at: a heat map of the
 * spectral abscissa (blue: stable, red: unstable, darker = further from the boundary; yellow: marginal or too
 * near to tell; black: ill-posed) with the thesis' closed-form boundary ((1.10), (1.12), (1.14)) drawn on top.
 *
 * Cells of one colour that follow each other in a row are one <rect>, so a smooth 1000 x 1000 map stays a few
 * MB. Colour depth is sqrt(|abscissa| / max |abscissa|) in 8 steps: the square root spreads the shades
 * near the boundary, where the eye wants detail.
 */
#include <math.h>
#include <stdio.h>

#include "stability_out.h"

enum { LEFT = 90, TOP = 50, SIDE = 560, RIGHT = 280, BOTTOM = 70, SHADES = 8 };

static const char *const BLUES[SHADES] = { "#deebf7", "#c6dbef", "#9ecae1", "#6baed6",
                                           "#4292c6", "#2171b5", "#08519c", "#08306b" };
static const char *const REDS[SHADES] = { "#fee0d2", "#fcbba1", "#fc9272", "#fb6a4a",
                                          "#ef3b2c", "#cb181d", "#a50f15", "#67000d" };
#define YELLOW "#f2c500"
#define BLACK "#000000"
#define GREY "#bdbdbd"

static double max_abs(const dp_map *map)
{
    double m = 0.0;
    for (size_t k = 0; k < map->nx * map->ny; k++)
        if (map->has_abscissa[k])
            m = fmax(m, fabs(map->abscissa[k]));
    return m;
}

static const char *colour(const dp_map *map, size_t k, double amax)
{
    switch (map->verdict[k]) {
    case DP_VERDICT_STABLE:
    case DP_VERDICT_UNSTABLE:
        if (!map->has_abscissa[k] || amax <= 0.0)
            return GREY;       /* no finite mode at all */
        break;
    case DP_VERDICT_ILL_POSED:
        return BLACK;
    default:
        return YELLOW;
    }
    int q = (int)ceil(sqrt(fabs(map->abscissa[k]) / amax) * SHADES) - 1;
    q = q < 0 ? 0 : q >= SHADES ? SHADES - 1 : q;
    return map->verdict[k] == DP_VERDICT_STABLE ? BLUES[q] : REDS[q];
}

static void cells(stab_out *o, const dp_map *map)
{
    double amax = max_abs(map);
    /* grid units, y up: cell (i, j) is [i, i+1] x [j, j+1] and its point sits at the centre */
    stab_printf(o, "<g transform=\"translate(%d,%d) scale(%.9g,%.9g)\" shape-rendering=\"crispEdges\">\n",
                LEFT, TOP + SIDE, (double)SIDE / map->nx, -(double)SIDE / map->ny);
    for (size_t j = 0; j < map->ny && !o->failed; j++) {
        size_t i = 0;
        while (i < map->nx) {
            const char *c = colour(map, j * map->nx + i, amax);
            size_t run = 1;
            while (i + run < map->nx && colour(map, j * map->nx + i + run, amax) == c)
                run++;
            stab_printf(o, "<rect x=\"%zu\" y=\"%zu\" width=\"%zu\" height=\"1\" fill=\"%s\"/>", i, j, run, c);
            i += run;
        }
        stab_put(o, "\n");
    }
    stab_put(o, "</g>\n");
}

static int segment(void *ctx, double x0, double y0, double x1, double y1)
{
    stab_out *o = ctx;
    stab_printf(o, "M%.6g %.6gL%.6g %.6g", x0 + 0.5, y0 + 0.5, x1 + 0.5, y1 + 0.5);
    return o->failed;
}

static void boundary(stab_out *o, const dp_map *map)
{
    if (map->closed_value == NULL)
        return;
    stab_printf(o, "<g transform=\"translate(%d,%d) scale(%.9g,%.9g)\">\n<path d=\"", LEFT, TOP + SIDE,
                (double)SIDE / map->nx, -(double)SIDE / map->ny);
    dp_map_boundary(map, segment, o);
    stab_put(o, "\" fill=\"none\" stroke=\"#000\" stroke-width=\"2.5\" "
                "vector-effect=\"non-scaling-stroke\"/>\n</g>\n");
}

static void axes(stab_out *o, const dp_map *map)
{
    char xn[32], yn[32];
    dp_param_name(map->x.kind, map->x.index, xn, sizeof xn);
    dp_param_name(map->y.kind, map->y.index, yn, sizeof yn);
    stab_printf(o, "<rect x=\"%d\" y=\"%d\" width=\"%d\" height=\"%d\" fill=\"none\" stroke=\"#333\"/>\n",
                LEFT, TOP, SIDE, SIDE);
    stab_printf(o, "<text x=\"%d\" y=\"%d\">%.6g</text>", LEFT, TOP + SIDE + 20, map->x.from);
    stab_printf(o, "<text x=\"%d\" y=\"%d\" text-anchor=\"end\">%.6g</text>", LEFT + SIDE, TOP + SIDE + 20,
                map->x.to);
    stab_printf(o, "<text x=\"%d\" y=\"%d\" text-anchor=\"middle\" font-weight=\"bold\">%s</text>\n",
                LEFT + SIDE / 2, TOP + SIDE + 45, xn);
    stab_printf(o, "<text x=\"%d\" y=\"%d\" text-anchor=\"end\">%.6g</text>", LEFT - 6, TOP + SIDE, map->y.from);
    stab_printf(o, "<text x=\"%d\" y=\"%d\" text-anchor=\"end\">%.6g</text>", LEFT - 6, TOP + 12, map->y.to);
    stab_printf(o, "<text x=\"%d\" y=\"%d\" text-anchor=\"middle\" font-weight=\"bold\" "
                   "transform=\"rotate(-90 %d %d)\">%s</text>\n",
                LEFT - 45, TOP + SIDE / 2, LEFT - 45, TOP + SIDE / 2, yn);
}

static void swatch(stab_out *o, int row, const char *fill, const char *label)
{
    int x = LEFT + SIDE + 20, y = TOP + 10 + 24 * row;
    stab_printf(o, "<rect x=\"%d\" y=\"%d\" width=\"16\" height=\"16\" fill=\"%s\" stroke=\"#333\"/>"
                   "<text x=\"%d\" y=\"%d\">%s</text>\n", x, y, fill, x + 24, y + 13, label);
}

static void legend(stab_out *o, const dp_map *map)
{
    swatch(o, 0, BLUES[SHADES - 1], "stable, far from boundary");
    swatch(o, 1, BLUES[0], "stable, near boundary");
    swatch(o, 2, REDS[0], "unstable, near boundary");
    swatch(o, 3, REDS[SHADES - 1], "unstable, far from boundary");
    swatch(o, 4, YELLOW, "marginal / too near to tell");
    swatch(o, 5, BLACK, "ill-posed (singular pencil)");
    swatch(o, 6, GREY, "no finite mode");
    if (map->closed_value != NULL) {
        int x = LEFT + SIDE + 20, y = TOP + 10 + 24 * 7 + 8;
        stab_printf(o, "<path d=\"M%d %dh16\" stroke=\"#000\" stroke-width=\"2.5\"/>"
                       "<text x=\"%d\" y=\"%d\">Babováková 2012 §%s, %s = 0</text>\n",
                    x, y, x + 24, y + 5, map->closed.name, map->closed.condition);
    }
    stab_printf(o, "<text x=\"%d\" y=\"%d\">max |spectral abscissa| = %.4g</text>\n", LEFT + SIDE + 20,
                TOP + 10 + 24 * 9, max_abs(map));
}

void stab_map_svg(stab_out *o, const dp_map *map)
{
    stab_printf(o, "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%d\" height=\"%d\" "
                   "font-family=\"sans-serif\" font-size=\"13\">\n", LEFT + SIDE + RIGHT, TOP + SIDE + BOTTOM);
    stab_printf(o, "<rect width=\"100%%\" height=\"100%%\" fill=\"#fff\"/>\n<text x=\"%d\" y=\"30\" "
                   "font-size=\"16\">Stability map: spectral abscissa of m z^2 lambda(z) + mu(z) "
                   "(%zu x %zu points)</text>\n", LEFT, map->nx, map->ny);
    cells(o, map);
    boundary(o, map);
    axes(o, map);
    legend(o, map);
    stab_put(o, "</svg>\n");
}
