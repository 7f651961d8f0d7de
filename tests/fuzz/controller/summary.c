#include "summary.h"

#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>

#include "fw/proto.h"

/* The rig's operations by name (fuzz_controller.c). */
extern const char *const fuzz_op_names[];
extern const unsigned fuzz_op_count;

#define MAX_OPS 32

static struct {
    unsigned long inputs, homed;
    unsigned long transitions[FW_STATE_COUNT][FW_STATE_COUNT];
    unsigned long acks[128], rejects[128], reasons[FW_REASON_COUNT];
    unsigned long faults[FW_FAULT_COUNT];
    unsigned long ops[MAX_OPS];
} sum;

static void print(void)
{
    printf("controller fuzz summary: %lu inputs, %lu homings completed\n", sum.inputs, sum.homed);
    printf("states entered (times):");
    for (int to = 0; to < FW_STATE_COUNT; ++to) {
        unsigned long n = 0;
        for (int from = 0; from < FW_STATE_COUNT; ++from)
            n += from != to ? sum.transitions[from][to] : 0;
        printf(" %s %lu", proto_enum_name(proto_state_names, to), n);
    }
    printf("\ntransitions:");
    for (int from = 0; from < FW_STATE_COUNT; ++from)
        for (int to = 0; to < FW_STATE_COUNT; ++to)
            if (from != to && sum.transitions[from][to])
                printf(" %s>%s %lu", proto_enum_name(proto_state_names, from),
                       proto_enum_name(proto_state_names, to), sum.transitions[from][to]);
    printf("\nanswers (acks/rejects):");
    for (int i = 0; i < PM_COUNT; ++i) {
        const uint8_t fn = proto_table[i].function;
        if (proto_table[i].dir == PROTO_TO_CONTROLLER && (sum.acks[fn] || sum.rejects[fn]))
            printf(" %s %lu/%lu", proto_table[i].name, sum.acks[fn], sum.rejects[fn]);
    }
    unsigned long unknown = 0;
    for (int fn = 0; fn < 128; ++fn)
        if (!proto_lookup((uint8_t)fn, PROTO_TO_CONTROLLER))
            unknown += sum.rejects[fn];
    printf(" (unknown functions) 0/%lu\nreject reasons:", unknown);
    for (int i = 1; i < FW_REASON_COUNT; ++i)
        printf(" %s %lu", proto_enum_name(proto_reason_names, i), sum.reasons[i]);
    printf("\nfaults latched:");
    for (int i = 1; i < FW_FAULT_COUNT; ++i)
        printf(" %s %lu", proto_enum_name(proto_fault_names, i), sum.faults[i]);
    printf("\nrig operations:");
    for (unsigned i = 0; i < fuzz_op_count && i < MAX_OPS; ++i)
        printf(" %s %lu", fuzz_op_names[i], sum.ops[i]);
    printf("\n");
}

void summary_input(void)
{
    static bool asked;
    if (!asked) {
        asked = true;
        if (getenv("TSE_FUZZ_SUMMARY"))
            atexit(print);
    }
    ++sum.inputs;
}

void summary_state(fw_state from, fw_state to)
{
    if ((unsigned)from < FW_STATE_COUNT && (unsigned)to < FW_STATE_COUNT)
        ++sum.transitions[from][to];
}

void summary_answer(uint8_t function, int rejected, fw_reason reason)
{
    function &= 0x7F;
    if (rejected) {
        ++sum.rejects[function];
        if ((unsigned)reason < FW_REASON_COUNT)
            ++sum.reasons[reason];
    } else {
        ++sum.acks[function];
    }
}

void summary_fault(fw_fault f)
{
    if ((unsigned)f < FW_FAULT_COUNT)
        ++sum.faults[f];
}

void summary_op(unsigned op)
{
    if (op < MAX_OPS)
        ++sum.ops[op];
}

void summary_homed(void)
{
    ++sum.homed;
}
