/* params list | get NAME | set NAME VALUE | dump [FILE] | save, in SI units (the wire stays integer). */
#include <stdio.h>
#include <string.h>

#include "commands.h"
#include "ctl_info.h"
#include "ctl_params.h"
#include "param_text.h"

/* "name = value unit", the value in k's spelling. */
static void print_value(const char *name, const param_key *k, int32_t raw)
{
    char v[64];
    printf("%s = %s%s%s\n", name, param_to_text(k, raw, v, sizeof v), *k->unit ? " " : "", k->unit);
}

static void list(void)
{
    printf("%-15s %-12s %-9s %-26s %s\n", "name", "default", "unit", "range", "meaning");
    for (int id = 0; id < FP_COUNT; ++id) {
        param_key k;
        param_si_key(id, &k);
        char d[48], lo[48], hi[48], range[100];
        param_to_text(&k, fw_param_table[id].def, d, sizeof d);
        snprintf(range, sizeof range, "%s..%s", param_to_text(&k, fw_param_table[id].min, lo, sizeof lo),
                 param_to_text(&k, fw_param_table[id].max, hi, sizeof hi));
        printf("%-15s %-12s %-9s %-26s %s\n", fw_param_table[id].name, d, *k.unit ? k.unit : "-", range,
               fw_param_table[id].doc);
    }
    printf("\nValues are in SI (m, rad, m/s, ratios) unless the name carries its unit (_ms, _ns, _kbps);\n"
           "angles may also be given in degrees as NAME_deg (e.g. 'params set eta_deg 30').\n");
    fw_param_set d;
    fw_params_default(&d);
    char speed[512];
    printf("\nA slide's speed is held to the lower of slide_vmax and the step generator's limit; with the\n"
           "defaults ('tsectl params get slide_vmax' shows a controller's):\n%s\n",
           param_speed_limit_words(&d, FW_RATES_BUILT_IN, speed, sizeof speed));
}

/* After a value of the speed limit's parameters, the limit it gives with the controller's others
 * at its rates, as a comment line (the output stays a parameter file). */
static void speed_note(tlink *l, int id, int32_t raw)
{
    fw_param_set s;
    fw_rates r;
    if (!param_sets_speed_limit(id) || ctl_params_read(l, &s) != EXIT_OK || ctl_rates(l, &r) != EXIT_OK)
        return;
    s.v[id] = raw;
    char speed[512];
    printf("# %s\n", param_speed_limit_words(&s, r, speed, sizeof speed));
}

/* After a set of a parameter the board takes at start-up only (docs/protocol.md, "Parameters"),
 * that the controller holds it but runs on as before until a save and a restart. */
static void start_note(const tlink *l, int id)
{
    if (id != FP_CAN_KBPS && id != FP_NODE && id != FP_ENABLE_LEVEL)
        return;
    printf("# stored, not yet in effect: node %u takes %s at start-up ('params save', then restart it)%s\n", l->node,
           fw_param_table[id].name, id == FP_NODE ? "; until then it answers on its current id" : "");
}

/* Checks NAME and VALUE of a set before anything is sent. */
static int parse_set(char **argv, param_key *k, int32_t *raw)
{
    if (param_lookup(argv[1], k) != 0)
        return usage_error("params", "unknown parameter (see 'tsectl params list')", argv[1]);
    char err[256];
    if (param_from_text(k, argv[2], raw, err, sizeof err) != 0)
        return usage_error("params", err, NULL);
    return EXIT_OK;
}

/* A parameter file's set as a controller would hold it, without a bus: the file read as tse-sim
 * reads it (param_file_read over the defaults), refused with the reader's message (exit 2). */
static int dump_file(const char *path)
{
    fw_param_set s;
    fw_params_default(&s);
    char err[512];
    if (param_file_read(path, &s, FW_RATES_BUILT_IN, err, sizeof err) != 0) {
        fprintf(stderr, "tsectl: %s\n", err);
        return EXIT_USAGE;
    }
    char title[320];
    snprintf(title, sizeof title, "parameters of %.200s as a controller takes them (SI units, each unit in a comment)",
             path);
    param_file_dump(stdout, &s, FW_RATES_BUILT_IN, title);
    return EXIT_OK;
}

int check_params(int argc, char **argv, int *done)
{
    if (argc < 1)
        return usage_error("params", "needs list, get NAME, set NAME VALUE, dump or save", NULL);
    const char *sub = argv[0];
    param_key k;
    if (!strcmp(sub, "list")) {
        if (argc > 1)
            return usage_error("params", "unexpected argument", argv[1]);
        list();
        *done = 1;
        return EXIT_OK;
    }
    if (!strcmp(sub, "dump") && argc == 2) {
        *done = 1;
        return dump_file(argv[1]);
    }
    if (!strcmp(sub, "save") || !strcmp(sub, "dump"))
        return argc > 1 ? usage_error("params", "unexpected argument", argv[argc - 1]) : EXIT_OK;
    if (!strcmp(sub, "get")) {
        if (argc != 2)
            return usage_error("params", "get takes one NAME", argc > 2 ? argv[2] : NULL);
        return param_lookup(argv[1], &k) == 0 ? EXIT_OK
                                               : usage_error("params", "unknown parameter (see 'tsectl params list')", argv[1]);
    }
    if (!strcmp(sub, "set")) {
        if (argc != 3)
            return usage_error("params", "set takes NAME VALUE", argc > 3 ? argv[3] : NULL);
        int32_t raw;
        return parse_set(argv, &k, &raw);
    }
    return usage_error("params", "unknown subcommand", sub);
}

/* A PARAM_SET refused for the whole set: the rule the controller named, with its values and the
 * controller's others.  From a controller that names no rule, tsectl's own judgement at its rates,
 * if any, all at the controller's rates (INFO's). */
static void explain_set(tlink *l, int id, int32_t raw, const proto_message *rej)
{
    fw_param_set s;
    fw_rates r;
    if (ctl_params_read(l, &s) != EXIT_OK || ctl_rates(l, &r) != EXIT_OK)
        return;
    s.v[id] = raw;
    fw_param_fault f = {id, (fw_param_rule)rej->v[6]};
    if (f.rule == FW_RULE_NONE)
        f = fw_params_judge_config(&s, r.step_hz, r.segment_hz);
    if (f.rule == FW_RULE_NONE)
        return;
    char why[512];
    param_explain_fault(&s, f, r, why, sizeof why);
    ctl_error("why: %s", why);
}

int run_params(tlink *l, int argc, char **argv)
{
    (void)argc;
    const char *sub = argv[0];
    if (!strcmp(sub, "save")) {
        const int rc = ctl_params_save(l);
        if (rc == EXIT_OK)
            printf("parameters saved\n");
        return rc;
    }
    if (!strcmp(sub, "dump")) {
        fw_param_set s;
        fw_rates r;
        int rc = ctl_params_read(l, &s);
        if (rc == EXIT_OK)
            rc = ctl_rates(l, &r);
        if (rc != EXIT_OK)
            return rc;
        char title[160];
        snprintf(title, sizeof title,
                 "parameters of node %u (SI units, each unit in a comment; tse-sim --params and tse-kin --params "
                 "read this file)",
                 l->node);
        param_file_dump(stdout, &s, r, title);
        return EXIT_OK;
    }
    param_key k;
    if (!strcmp(sub, "get")) {
        param_lookup(argv[1], &k);
        int32_t raw;
        const int rc = ctl_param_get(l, k.id, &raw);
        if (rc == EXIT_OK) {
            print_value(argv[1], &k, raw);
            speed_note(l, k.id, raw);
        }
        return rc;
    }
    int32_t raw = 0; /* (set by parse_set when it returns EXIT_OK) */
    if (parse_set(argv, &k, &raw) != EXIT_OK)
        return EXIT_USAGE;
    proto_message rej;
    int32_t now;
    const int rc = ctl_param_set(l, k.id, raw, &now, &rej);
    if (rc == EXIT_REJECTED) {
        ctl_print_reject(&rej);
        if (rej.v[2] == FW_REASON_PARAM_SET)
            explain_set(l, k.id, raw, &rej);
        return rc;
    }
    if (rc == EXIT_OK) {
        print_value(argv[1], &k, now);
        speed_note(l, k.id, now);
        start_note(l, k.id);
    }
    return rc;
}
