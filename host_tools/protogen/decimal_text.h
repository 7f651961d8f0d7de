/* Numbers as text that a reader parses back to exactly what the table means.
 *
 * A DBC range or factor printed with a fixed number of digits is rounded: [1.16328072e+09|...]
 * excludes the value it describes.  These print a double as the shortest decimal that reads back as
 * the same double, and raw x scale as the exact decimal product of the integer and that decimal
 * (so 2147483647 x 1e-9 is 2.147483647, never rounded either way). */
#ifndef PROTOGEN_DECIMAL_TEXT_H
#define PROTOGEN_DECIMAL_TEXT_H

#include <stddef.h>
#include <stdint.h>

/* The shortest "%.*g" text of x that strtod reads back as x.  Returns 0, or -1 when x is not
 * finite or the text does not fit in n bytes. */
int dec_shortest(double x, char *out, size_t n);

/* raw times the shortest decimal of scale, exactly, in plain notation (no exponent, no trailing
 * zeros after a point, "0" for zero).  Returns 0, or -1 when scale is not finite or the text does
 * not fit in n bytes. */
int dec_scaled(int64_t raw, double scale, char *out, size_t n);

#endif
