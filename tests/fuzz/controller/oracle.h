/* The controller fuzz target's judge: what docs/controller.md (the controller's behaviour) and
 * docs/protocol.md promise, checked after every frame, poll, control tick and step pulse (the
 * rig calls these at those points).  A broken promise aborts through FUZZ_CHECK.
 *
 * It keeps its own model of what the host has been told (the parameter set in force and the one
 * saved, the staged pose, the last commit spent, whether a stopped trajectory is still draining),
 * built from the frames it saw answered, and holds the controller to it. */
#ifndef FUZZ_CONTROLLER_ORACLE_H
#define FUZZ_CONTROLLER_ORACLE_H

#include <stdbool.h>
#include <stdint.h>

#include "rig.h"

/* The controller has just been initialised.  saved: the parameter record the fake flash holds,
 * or NULL for none (the defaults). */
void oracle_start(rig *r, const fw_param_set *saved);
/* ... initialised again after a power cycle: with the set last saved. */
void oracle_reboot(rig *r);

/* A frame is about to be fed (every periodic output has been flushed before). */
void oracle_before_frame(rig *r, const hal_can_frame *f);
/* Its poll has run: its answers and effects. */
void oracle_after_frame(rig *r);
/* A poll without a frame. */
void oracle_after_poll(rig *r);
/* An input changed, or the platform reported a fault, between two calls into the controller. */
void oracle_event(rig *r);
/* The platform reported a fault (fw_report_fault), which publishes the view as it stands, between
 * two control ticks: SLIDES may say the steps as of then, until the next tick publishes. */
void oracle_published(rig *r);
/* A control tick. */
void oracle_after_control(rig *r);
/* A control-segment boundary, before its poll. */
void oracle_segment(rig *r);

/* The e-stop interrupt fired: between two calls into the controller, or inside one (from a fake
 * hook point), which then need not complete it. */
void oracle_estop_isr(rig *r, bool inside);
/* A frame the controller sends, as it sends it (board timing: a tick may change what it reports
 * before the outputs are read, so STATUS is judged here then). */
void oracle_sent(rig *r, const hal_can_frame *f);
/* The stepper outputs, before the fake takes them. */
void oracle_pulse(rig *r, uint8_t mask);
void oracle_dir(rig *r, uint8_t forward_mask);

#endif
