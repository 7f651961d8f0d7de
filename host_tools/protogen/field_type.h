/* Width, signedness and name of a wire field type, for the documents (the codec keeps its own
 * byte sizes in proto.c). */
#ifndef PROTOGEN_FIELD_TYPE_H
#define PROTOGEN_FIELD_TYPE_H

#include "fw/proto_table.h"

static inline int ft_bits(proto_field_type t)
{
    static const int bits[] = {8, 8, 16, 16, 24, 24, 32, 32};
    return bits[t];
}

static inline int ft_signed(proto_field_type t)
{
    return t == PF_I8 || t == PF_I16 || t == PF_I24 || t == PF_I32;
}

static inline const char *ft_name(proto_field_type t)
{
    static const char *const names[] = {"u8", "i8", "u16", "i16", "u24", "i24", "u32", "i32"};
    return names[t];
}

#endif
