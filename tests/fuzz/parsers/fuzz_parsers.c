/* The host tools' text parsers on any input.
 *
 * Input byte 0 picks the parser (byte 0 % 5) and a few options (byte 0 / 5); the rest is the text:
 *  0  one CSV row (csv_parse_fields, at most 1..16 numbers);
 *  1  tse-kin's row loop (stream_rows) over it as stdin, shaped as ik, fk or jacobian;
 *  2  a trajectory file (traj_file_read);
 *  3  a tse-kin parameter file (kin_params_parse), over the defaults or another base (opt bit 0),
 *     as a controller's set or a design (opt bit 1);
 *  4  a controller SI parameter file (param_file_read), over the defaults or another base.
 * Each case (checks.h) compares the parser's answer with the rules of its header read
 * independently (ref_text.h and the case's own reference), checks the promises on an accepted
 * input (values finite and in range, sets that the library or firmware accepts, numbers and sets
 * that read back to themselves once written), and on a refused one the message (NAME:LINE: or
 * NAME: ...) and the output left as it was. */
#include "checks.h"
#include "fuzz_target.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size == 0)
        return 0;
    static void (*const cases[])(const char *, size_t, unsigned) = {
        check_csv_row, check_kin_stream, check_traj_file, check_kin_params, check_param_file,
    };
    const unsigned which = data[0] % 5u, opt = data[0] / 5u;
    cases[which]((const char *)data + 1, size - 1, opt);
    return 0;
}
