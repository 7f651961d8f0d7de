/* STEP, DIR and ENABLE outputs on the description's pins.  A STEP pulse rises in the step
 * interrupt and falls when TIM4, started as a one-shot of step_pulse_ns, runs out: the width is
 * the drivers' parameter, whatever the step rate, and no interrupt time is spent waiting.
 *
 * Where the six STEP pins share a port (and likewise DIR) a mask of slides is one BSRR write
 * through a 64-entry table of that port's bits; where they do not, each slide's pin is written
 * from a small table of port and bit per slide.  Both tables are built once, by
 * board_stepper_hal, from the description. */
#include "hal_stm32f4/board_io.h"
#include "hal_stm32f4/board_pins.h"
#include "hal_stm32f4/fault.h"
#include "hal_stm32f4/regs_core.h"
#include "hal_stm32f4/regs_tim.h"

#define PRIO_PULSE 1u
#define ALL 0x3Fu

typedef struct {
    volatile uint32_t *bsrr;
    uint32_t bit;
} slide_pin;

/* One signal of the six slides (STEP or DIR). */
typedef struct {
    volatile uint32_t *bsrr; /* the shared port's BSRR, or NULL: per slide */
    uint16_t bits[ALL + 1u]; /* shared port: the port's bits of each mask of slides */
    slide_pin slide[BOARD_SLIDES];
} signal_out;

static struct {
    uint32_t timer_hz;
    uint32_t pulse_ticks;
    signal_out step, dir;
    slide_pin enable[BOARD_SLIDES];
    unsigned enables;
    bool enable_high;
} out;

static const board_desc *outputs_desc = &tse_board_desc;

static void build(signal_out *s, const uint8_t pins[BOARD_SLIDES])
{
    bool shared = true;
    for (unsigned k = 0; k < BOARD_SLIDES; ++k) {
        s->slide[k] = (slide_pin){&board_pin_port(pins[k])->BSRR, 1u << BOARD_PIN_NUM(pins[k])};
        shared = shared && BOARD_PIN_PORT(pins[k]) == BOARD_PIN_PORT(pins[0]);
    }
    s->bsrr = shared ? s->slide[0].bsrr : 0;
    for (unsigned m = 0; m <= ALL; ++m) {
        uint32_t b = 0;
        for (unsigned k = 0; k < BOARD_SLIDES; ++k)
            if ((m >> k) & 1u)
                b |= s->slide[k].bit;
        s->bits[m] = (uint16_t)b;
    }
}

/* Sets the pins of `high` and clears those of `low` (masks of slides). */
static inline void put_pins(const signal_out *s, uint32_t high, uint32_t low)
{
    if (s->bsrr) {
        *s->bsrr = s->bits[high] | (uint32_t)s->bits[low] << 16;
        return;
    }
    for (unsigned k = 0; k < BOARD_SLIDES; ++k) {
        if ((high >> k) & 1u)
            *s->slide[k].bsrr = s->slide[k].bit;
        else if ((low >> k) & 1u)
            *s->slide[k].bsrr = s->slide[k].bit << 16;
    }
}

static void set_dir(void *ctx, uint8_t forward)
{
    (void)ctx;
    const uint32_t f = forward & ALL;
    put_pins(&out.dir, f, ~f & ALL);
}

static void pulse(void *ctx, uint8_t mask)
{
    (void)ctx;
    put_pins(&out.step, mask & ALL, 0);
    /* (Re)start the one-shot: a pulse of another axis still high is lengthened, never cut. */
    TSE_TIM4->CNT = 0;
    TSE_TIM4->CR1 = TIM_CR1_OPM | TIM_CR1_URS | TIM_CR1_CEN;
}

void TIM4_IRQHandler(void);
void TIM4_IRQHandler(void)
{
    TSE_TIM4->SR = 0;
    TSE_TIM4->CR1 = TIM_CR1_OPM | TIM_CR1_URS; /* stopped, should the one-pulse mode not be */
    put_pins(&out.step, 0, ALL);
}

static void drive_enable(bool on)
{
    const bool high = on == out.enable_high;
    for (unsigned i = 0; i < out.enables; ++i)
        *out.enable[i].bsrr = high ? out.enable[i].bit : out.enable[i].bit << 16;
}

static void enable(void *ctx, bool on)
{
    (void)ctx;
    drive_enable(on);
}

static void timing(void *ctx, uint32_t pulse_ns, uint32_t dir_setup_ns)
{
    (void)ctx;
    (void)dir_setup_ns; /* the step generator keeps it, in step interrupts */
    /* Rounded up: a pulse is never shorter than asked. */
    uint64_t ticks = ((uint64_t)pulse_ns * out.timer_hz + 999999999u) / 1000000000u;
    if (ticks < 2u)
        ticks = 2u;
    if (ticks > 0xFFFFu)
        ticks = 0xFFFFu;
    out.pulse_ticks = (uint32_t)ticks;
    TSE_TIM4->ARR = out.pulse_ticks;
}

/* The outputs' tables from d, the ENABLE level from the argument or d. */
static void bind(const board_desc *d, int enable_active_high)
{
    outputs_desc = d;
    build(&out.step, d->step);
    build(&out.dir, d->dir);
    out.enables = 0;
    for (unsigned i = 0; i < BOARD_SLIDES; ++i)
        if (d->enable[i] != BOARD_PIN_NONE)
            out.enable[out.enables++] =
                (slide_pin){&board_pin_port(d->enable[i])->BSRR, 1u << BOARD_PIN_NUM(d->enable[i])};
    out.enable_high = enable_active_high < 0 ? d->enable_active_high != 0 : enable_active_high != 0;
}

hal_stepper board_stepper_hal_for(const board_desc *d, uint32_t timer_hz, int enable_active_high)
{
    bind(d, enable_active_high);
    drive_enable(false); /* inactive at its level at once, before the pin drives (board_pins_init) */
    out.timer_hz = timer_hz;
    TSE_TIM4->CR1 = 0;
    TSE_TIM4->PSC = 0;
    TSE_TIM4->EGR = TIM_EGR_UG; /* loads PSC */
    TSE_TIM4->SR = 0;
    TSE_TIM4->DIER = TIM_DIER_UIE;
    timing(0, 2500u, 0u); /* the DM542's 2.5 us until the controller programs step_pulse_ns */
    tse_nvic_enable(IRQ_TIM4, PRIO_PULSE);
    const hal_stepper h = {0, set_dir, pulse, enable, timing};
    return h;
}

hal_stepper board_stepper_hal(uint32_t timer_hz, int enable_active_high)
{
    return board_stepper_hal_for(&tse_board_desc, timer_hz, enable_active_high);
}

bool board_enable_active_high(void)
{
    return out.enables ? out.enable_high : outputs_desc->enable_active_high != 0;
}

void board_outputs_safe(void)
{
    TSE_TIM2->CR1 = 0; /* no further step interrupt */
    TSE_TIM2->DIER = 0;
    /* Before board_stepper_hal the tables are empty: the description's level and pins. */
    if (out.enables == 0)
        bind(outputs_desc, -1);
    drive_enable(false);
    put_pins(&out.step, 0, ALL);
}
