/* The controller's start and what the platform reads of it (fw/controller.h). */
#include "fw/controller.h"

#include "controller_internal.h"

#include <string.h>

#include "adopt.h"
#include "publish.h"
#include "state.h"

static bool config_runs(const fw_config *cfg)
{
    return cfg->node <= PROTO_NODE_MASK && fw_rates_run((fw_rates){cfg->step_hz, cfg->segment_hz});
}

void fw_params_stored(const hal_storage *storage, fw_param_set *s)
{
    fw_params_default(s);
    uint8_t buf[256];
    const int n = storage->load(storage->ctx, buf, sizeof buf);
    if (n > 0)
        fw_params_deserialize(s, buf, (size_t)n); /* a bad record leaves the defaults */
}

fw_controller *fw_init(fw_controller_mem *mem, const fw_hal *hal, const fw_config *cfg)
{
    fw_controller *c = (fw_controller *)(void *)mem;
    memset(c, 0, sizeof *c);
    if (!config_runs(cfg))
        return NULL;
    c->hal = *hal;
    c->cfg = *cfg;
    c->tick.state = FW_STATE_BOOT;
    atomic_init(&c->sh.estop_request, false);

    fw_param_set s;
    fw_params_stored(&hal->storage, &s);
    static fw_prepared_params p; /* large, and fw_init runs before anything else: off the stack */
    if (fw_params_prepare(c, &s, &p) != FW_RULE_NONE || fw_params_adopt(c, &p) != FW_RULE_NONE) {
        fw_params_default(&s);
        if (fw_params_prepare(c, &s, &p) != FW_RULE_NONE || fw_params_adopt(c, &p) != FW_RULE_NONE)
            return NULL;
    }
    c->th.params = p.s;
    /* The id it answers on until the next start: a PARAM_SET of node changes the stored value
     * only (docs/controller.md). */
    if (c->cfg.node == 0)
        c->cfg.node = (uint8_t)p.s.v[FP_NODE];
    c->th.geom = p.g;
    c->th.lim = p.lim;
    fw_traj_queue_start(&c->tick.traj, c->tick.geom.home_pose);
    fw_traj_queue_drop(&c->tick.traj);
    fw_traj_check_start(&c->th.traj, &c->th.lim, c->tick.geom.home_pose, c->tick.q);
    c->th.traj.closed = true;
    fw_drives(c, false);
    const uint64_t t = fw_now(c);
    c->th.next_status_us = t;
    c->th.next_telemetry_us = t;
    fw_set_state(c, FW_STATE_DISABLED);
    fw_publish(c);
    fw_view_read(c);
    return c;
}

void fw_report_fault(fw_controller *c, fw_fault f)
{
    fw_fault_raise(c, f);
    fw_publish(c);
}

fw_state fw_state_of(const fw_controller *c)
{
    return c->tick.state;
}

fw_fault fw_fault_of(const fw_controller *c)
{
    return c->tick.fault;
}

bool fw_homed_of(const fw_controller *c)
{
    return c->tick.homed;
}

bool fw_drives_of(const fw_controller *c)
{
    return c->tick.drives_on;
}

bool fw_boot_requested(const fw_controller *c)
{
    return c->th.boot_requested;
}

const fw_config *fw_config_of(const fw_controller *c)
{
    return &c->cfg;
}

const fw_param_set *fw_params_of(const fw_controller *c)
{
    return &c->tick.params;
}

const tse_geometry *fw_geometry_of(const fw_controller *c)
{
    return &c->tick.geom;
}

const fw_limits *fw_limits_of(const fw_controller *c)
{
    return &c->tick.lim;
}

const stepgen *fw_stepgen_of(const fw_controller *c)
{
    return &c->sg;
}
