/* The controller: the state machine of docs/controller.md, the CAN command handling, and the
 * execution of motion at the control segment rate.  Hardware-free: everything physical goes
 * through fw_hal.  How a platform runs it (its contexts and their order): fw/runtime.h.
 *
 * The controller is opaque: its layout is the firmware's own (firmware/src/controller_internal.h).
 * The platform gives it its hardware and room (fw/platform.h) and reads it through the accessors
 * below and fw/inspect.h.
 *
 * The homing switches (bit i of hal_inputs.limits) are references, not ends of travel: slide i's
 * is pressed at and below home_sw_i and released above it, and the slides go below it in
 * legitimate poses.  Homing sets each slide's coordinate at its switch's release edge.  Once
 * homed, a switch that disagrees with the step count by more than FW_HOME_SW_TOLERANCE_UM (lost
 * steps, or a broken switch) is FW_FAULT_LIMIT; before homing they are not checked.  The optional
 * high-end switches (bit 8 + i) are hard limits: pressed outside homing is FW_FAULT_LIMIT. */
#ifndef FW_CONTROLLER_H
#define FW_CONTROLLER_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "fw/move.h"
#include "fw/params.h"
#include "fw/platform.h"
#include "fw/stepgen.h"
#include "fw/types.h"

/* Loads the parameters from storage (defaults if none or corrupt) and enters DISABLED.  A
 * cfg->node of 0 takes the node id from the set it adopts.  Returns the controller (in mem), or
 * NULL for a configuration that cannot run.  Before the ticks start. */
fw_controller *fw_init(fw_controller_mem *mem, const fw_hal *hal, const fw_config *cfg);

/* The set storage holds (the defaults if it holds none, or a record that is not a valid set): what
 * fw_init starts from, for a platform that applies a parameter before it (the board's ENABLE
 * level, which its stepper needs before the controller drives it). */
void fw_params_stored(const hal_storage *storage, fw_param_set *s);

/* A fault the platform detected (the simulator's plant reports FW_FAULT_PLANT, the board
 * FW_FAULT_HARDWARE): a controlled stop if anything moves, then latched, exactly as the
 * controller's own faults.  From the control tick's context (after fw_control_tick), or before
 * the ticks start. */
void fw_report_fault(fw_controller *c, fw_fault f);

/* What tools and tests read: from the control tick's context, or where nothing runs at once (a
 * test between two calls).  The whole observable state: fw/inspect.h. */
fw_state fw_state_of(const fw_controller *c);
fw_fault fw_fault_of(const fw_controller *c);
bool fw_homed_of(const fw_controller *c);
bool fw_drives_of(const fw_controller *c);
/* BOOT_ENTER was accepted (with the drives off) and acknowledged: the platform should restart into
 * its bootloader, asking it to stay (docs/protocol.md, Updating the firmware), once the ACK is
 * on the bus.  Read by the thread after fw_poll; it never clears. */
bool fw_boot_requested(const fw_controller *c);
const fw_config *fw_config_of(const fw_controller *c);
const fw_param_set *fw_params_of(const fw_controller *c);
const tse_geometry *fw_geometry_of(const fw_controller *c);
const fw_limits *fw_limits_of(const fw_controller *c);
/* The step generator, for its configuration and positions (fw/stepgen.h: read-only). */
const stepgen *fw_stepgen_of(const fw_controller *c);

#endif
