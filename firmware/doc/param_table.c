/* The host's parameter table (fw/params.h), made from the list of parameters (fw/params.def). */
#include "fw/params.h"

#define FW_PARAM(id, name, unit, min, max, def, doc) [id] = {name, unit, min, max, def, doc},
const fw_param_def fw_param_table[FP_COUNT] = {
#include "fw/params.def"
};
