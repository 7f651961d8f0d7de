#include "wire_ref.h"

#include <stddef.h>

static const unsigned width[] = {[PF_U8] = 1, [PF_I8] = 1, [PF_U16] = 2, [PF_I16] = 2,
                                 [PF_U24] = 3, [PF_I24] = 3, [PF_U32] = 4, [PF_I32] = 4};

int64_t wire_ref_field(const uint8_t *data, const proto_field *fd)
{
    const unsigned n = width[fd->type];
    uint64_t raw = 0;
    for (unsigned k = 0; k < n; ++k)
        raw |= (uint64_t)data[fd->offset + k] << (8u * k);
    const int is_signed = fd->type == PF_I8 || fd->type == PF_I16 || fd->type == PF_I24 || fd->type == PF_I32;
    if (is_signed && (raw >> (8u * n - 1u)) & 1u)
        return (int64_t)raw - ((int64_t)1 << (8u * n));
    return (int64_t)raw;
}

const proto_def *wire_ref_entry(uint8_t function, proto_direction dir)
{
    for (int i = 0; i < PM_COUNT; ++i)
        if (proto_table[i].function == function && proto_table[i].dir == dir)
            return &proto_table[i];
    return NULL;
}
