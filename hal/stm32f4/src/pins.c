/* Pin configuration and the switch inputs, on the pins of the board's description
 * (board_desc.h). */
#include "hal_stm32f4/board_io.h"
#include "hal_stm32f4/board_desc.h"
#include "hal_stm32f4/board_pins.h"

static void set_mode(tse_gpio_regs *port, unsigned pin, uint32_t mode)
{
    port->MODER = (port->MODER & ~(3u << (2u * pin))) | mode << (2u * pin);
}

static void set_pull_up(tse_gpio_regs *port, unsigned pin)
{
    port->PUPDR = (port->PUPDR & ~(3u << (2u * pin))) | GPIO_PULL_UP << (2u * pin);
}

/* An output at `level` before it drives: STEP low, DIR low, the drivers disabled, the LED off. */
static void output(uint8_t p, bool level)
{
    if (p == BOARD_PIN_NONE)
        return;
    tse_gpio_regs *port = board_pin_port(p);
    const unsigned pin = BOARD_PIN_NUM(p);
    port->BSRR = 1u << (pin + (level ? 0u : 16u));
    port->OSPEEDR = (port->OSPEEDR & ~(3u << (2u * pin))) | GPIO_SPEED_HIGH << (2u * pin);
    set_mode(port, pin, GPIO_MODE_OUTPUT);
}

static void input(uint8_t p)
{
    if (p == BOARD_PIN_NONE)
        return;
    set_pull_up(board_pin_port(p), BOARD_PIN_NUM(p));
    set_mode(board_pin_port(p), BOARD_PIN_NUM(p), GPIO_MODE_INPUT);
}

void board_pin_alternate(uint8_t p, unsigned af)
{
    tse_gpio_regs *port = board_pin_port(p);
    const unsigned pin = BOARD_PIN_NUM(p);
    port->AFR[pin >> 3] = (port->AFR[pin >> 3] & ~(0xFu << (4u * (pin & 7u)))) | af << (4u * (pin & 7u));
    port->OSPEEDR |= GPIO_SPEED_HIGH << (2u * pin);
    set_mode(port, pin, GPIO_MODE_AF);
}

void board_pins_init(void)
{
    const board_desc *d = &tse_board_desc;
    for (unsigned k = 0; k < BOARD_SLIDES; ++k) {
        output(d->step[k], false);
        output(d->dir[k], false);
        output(d->enable[k], !board_enable_active_high()); /* the drivers disabled */
        input(d->lim[k]);
        input(d->limh[k]);
    }
    output(d->led, !d->led_active_high);
    input(d->estop);
    board_pin_alternate(d->can_rx, d->can_af);
    board_pin_alternate(d->can_tx, d->can_af);
    /* a recessive bus when no transceiver is fitted */
    set_pull_up(board_pin_port(d->can_rx), BOARD_PIN_NUM(d->can_rx));
}

void board_led_set(bool on)
{
    const board_desc *d = &tse_board_desc;
    if (d->led == BOARD_PIN_NONE)
        return;
    const uint32_t bit = 1u << BOARD_PIN_NUM(d->led);
    board_pin_port(d->led)->BSRR = on == (d->led_active_high != 0) ? bit : bit << 16;
}

static bool pin_high(uint8_t p)
{
    return (board_pin_port(p)->IDR >> BOARD_PIN_NUM(p)) & 1u;
}

/* In the control tick, not the step interrupt: a loop over the six is cheap enough there. */
static uint16_t limits(void *ctx)
{
    (void)ctx;
    const board_desc *d = &tse_board_desc;
    uint16_t v = 0;
    for (unsigned k = 0; k < BOARD_SLIDES; ++k) {
        if (pin_high(d->lim[k]))
            v |= (uint16_t)(1u << k);
        if (((d->limh_fitted >> k) & 1u) && d->limh[k] != BOARD_PIN_NONE && pin_high(d->limh[k]))
            v |= (uint16_t)(1u << (8u + k));
    }
    return v;
}

static bool estop(void *ctx)
{
    (void)ctx;
    return pin_high(tse_board_desc.estop);
}

hal_inputs board_inputs_hal(void)
{
    const hal_inputs h = {0, limits, estop};
    return h;
}
