/* Pin configuration and the switch inputs (pinmap.h). */
#include "hal_stm32f4/board_io.h"
#include "hal_stm32f4/pinmap.h"

static void set_mode(tse_gpio_regs *port, unsigned pin, uint32_t mode)
{
    port->MODER = (port->MODER & ~(3u << (2u * pin))) | mode << (2u * pin);
}

static void set_pull_up(tse_gpio_regs *port, unsigned pin)
{
    port->PUPDR = (port->PUPDR & ~(3u << (2u * pin))) | GPIO_PULL_UP << (2u * pin);
}

static void output_at(tse_gpio_regs *port, unsigned pin, bool high)
{
    port->BSRR = 1u << (pin + (high ? 0u : 16u)); /* its level before it drives */
    port->OSPEEDR = (port->OSPEEDR & ~(3u << (2u * pin))) | GPIO_SPEED_HIGH << (2u * pin);
    set_mode(port, pin, GPIO_MODE_OUTPUT);
}

static void output(tse_gpio_regs *port, unsigned pin)
{
    output_at(port, pin, false);
}

static void input(tse_gpio_regs *port, unsigned pin)
{
    set_pull_up(port, pin);
    set_mode(port, pin, GPIO_MODE_INPUT);
}

void board_pins_init(void)
{
    for (unsigned k = 0; k < 6; ++k) {
        output(PIN_STEP_PORT, PIN_STEP_SHIFT + k);
        output(PIN_DIR_PORT, PIN_DIR_SHIFT + k);
        input(PIN_LIM_PORT, PIN_LIM_SHIFT + k);
        input(PIN_LIMH_PORT, pin_limh[k]);
    }
    output_at(PIN_ENABLE_PORT, PIN_ENABLE, !board_enable_active_high()); /* drivers disabled */
    output(PIN_LED_PORT, PIN_LED);
    input(PIN_ESTOP_PORT, PIN_ESTOP);
    const unsigned can[2] = {PIN_CAN_RX, PIN_CAN_TX};
    for (unsigned i = 0; i < 2; ++i) {
        const unsigned pin = can[i];
        PIN_CAN_PORT->AFR[pin >> 3] = (PIN_CAN_PORT->AFR[pin >> 3] & ~(0xFu << (4u * (pin & 7u)))) |
                                      PIN_CAN_AF << (4u * (pin & 7u));
        PIN_CAN_PORT->OSPEEDR |= GPIO_SPEED_HIGH << (2u * pin);
        set_mode(PIN_CAN_PORT, pin, GPIO_MODE_AF);
    }
    set_pull_up(PIN_CAN_PORT, PIN_CAN_RX); /* a recessive bus when no transceiver is fitted */
}

static uint16_t limits(void *ctx)
{
    (void)ctx;
    uint16_t v = (uint16_t)((PIN_LIM_PORT->IDR >> PIN_LIM_SHIFT) & STEP_MASK_ALL);
    const uint32_t high = PIN_LIMH_PORT->IDR;
    for (unsigned k = 0; k < 6; ++k)
        if (((BOARD_HIGH_SWITCHES >> k) & 1u) && ((high >> pin_limh[k]) & 1u))
            v |= (uint16_t)(1u << (8u + k));
    return v;
}

static bool estop(void *ctx)
{
    (void)ctx;
    return (PIN_ESTOP_PORT->IDR >> PIN_ESTOP) & 1u;
}

hal_inputs board_inputs_hal(void)
{
    const hal_inputs h = {0, limits, estop};
    return h;
}
