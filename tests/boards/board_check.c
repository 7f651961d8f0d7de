/* board_check: every board description (hal/stm32f4/boards/NAME.h) checked for what would make its
 * image wrong on the board, against the tables below, written from ST's documents, not from the
 * drivers:
 *   - two signals on one pin;
 *   - a pin the part's package does not have (STM32F405/407 datasheet DocID022152, its pin and ball
 *     definitions table: LQFP64 has PA0..15, PB0..15, PC0..15, PD2, PH0/PH1; LQFP100 ports A..E; LQFP144
 *     ports A..G; PH0/PH1 always), or a part in a package it does not come in (F407: LQFP100 and
 *     LQFP144, no LQFP64);
 *   - the crystal's pins PH0/PH1 used for a signal;
 *   - a CAN pin without CAN1 on alternate function 9 (the datasheet's alternate function mapping: CAN1_RX on PA11, PB8,
 *     PD0; CAN1_TX on PA12, PB9, PD1);
 *   - a boot-line TX pin without its USART's TX (the same table: USART1_TX PA9, PB6; USART2_TX PA2, PD5;
 *     USART3_TX PB10, PC10, PD8, all AF7; USART6_TX PC6, PG14, AF8);
 *   - an application address that is not a flash sector's start, a parameter log whose sectors
 *     the part lacks, differ in size, lie below the application or leave it less than its flash
 *     budget (RM0090 table 5: sectors 0..3 16 KiB from 0x08000000, 4 64 KiB, then 128 KiB each;
 *     a 512 KiB part ends with sector 7, a 1 MiB part with 11);
 *   - a PLL off SYSCLK 168 MHz or USB 48 MHz, or outside the VCO's ranges (the datasheet's
 *     "main PLL characteristics": input 1..2 MHz, VCO 100..432 MHz; M 2..63, N 50..432).
 *
 *   board_check                 every board: exit 0 when none has a finding, else 1
 *   board_check --planted NAME  a planted faulty description (tests/boards/planted/NAME.h): exit 0
 *                               when a finding names its fault (its BOARD_PLANTED_EXPECT), else 1
 * Findings are printed one a line: "board NAME: <what is wrong>". */
#include <stdarg.h>
#include <stdbool.h>
#include <stdio.h>
#include <string.h>

#include "board_list.h"

#define IMAGE_BUDGET (96u * 1024u) /* board/CMakeLists.txt's TSE_FLASH_BUDGET */

static char findings[32][200];
static unsigned n_findings;
static const char *current;

static void finding(const char *fmt, ...)
{
    char text[160];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(text, sizeof text, fmt, ap);
    va_end(ap);
    printf("board %s: %s\n", current, text);
    if (n_findings < sizeof findings / sizeof findings[0])
        snprintf(findings[n_findings++], sizeof findings[0], "%s", text);
}

static const char *name_of(uint8_t p)
{
    static char buf[4][8];
    static unsigned next;
    char *b = buf[next++ % 4u];
    snprintf(b, sizeof buf[0], "P%c%u", 'A' + (p >> 4), p & 15u);
    return b;
}

/* The datasheet's pin definitions: does the package have the pin? */
static bool on_package(unsigned package, uint8_t p)
{
    const unsigned port = p >> 4, n = p & 15u;
    if (port == 7u) /* PH0/PH1 (OSC_IN/OSC_OUT) on every package */
        return n <= 1u;
    switch (package) {
    case 64:
        return port <= 2u || (port == 3u && n == 2u);
    case 100:
        return port <= 4u;
    case 144:
        return port <= 6u;
    default:
        return false;
    }
}

/* The datasheet's alternate function mapping: CAN1 on AF9. */
static bool can1_af9(uint8_t p, bool rx)
{
    static const char *const rx_pins[] = {"PA11", "PB8", "PD0"};
    static const char *const tx_pins[] = {"PA12", "PB9", "PD1"};
    const char *const *set = rx ? rx_pins : tx_pins;
    for (unsigned i = 0; i < 3; ++i)
        if (strcmp(set[i], name_of(p)) == 0)
            return true;
    return false;
}

/* The same: the TX pins of each USART and their AF. */
static const struct {
    unsigned usart, af;
    const char *pin;
} usart_tx[] = {
    {1, 7, "PA9"}, {1, 7, "PB6"}, {2, 7, "PA2"}, {2, 7, "PD5"}, {3, 7, "PB10"},
    {3, 7, "PC10"}, {3, 7, "PD8"}, {6, 8, "PC6"}, {6, 8, "PG14"},
};

/* RM0090 table 5. */
static const struct {
    uint32_t addr, kib;
} sectors[12] = {
    {0x08000000u, 16}, {0x08004000u, 16}, {0x08008000u, 16}, {0x0800C000u, 16},
    {0x08010000u, 64}, {0x08020000u, 128}, {0x08040000u, 128}, {0x08060000u, 128},
    {0x08080000u, 128}, {0x080A0000u, 128}, {0x080C0000u, 128}, {0x080E0000u, 128},
};

static unsigned sectors_of(unsigned flash_kib)
{
    return flash_kib == 512u ? 8u : flash_kib == 1024u ? 12u : 0u;
}

typedef struct {
    uint8_t pin;
    char what[24];
} use;

static void add(use *u, unsigned *n, uint8_t pin, const char *fmt, unsigned k)
{
    if (pin == BOARD_PIN_NONE)
        return;
    u[*n].pin = pin;
    snprintf(u[*n].what, sizeof u[*n].what, fmt, k);
    ++*n;
}

static void check_pins(const board_desc *d)
{
    use u[48];
    unsigned n = 0;
    for (unsigned k = 0; k < BOARD_SLIDES; ++k) {
        if (d->step[k] == BOARD_PIN_NONE || d->dir[k] == BOARD_PIN_NONE || d->lim[k] == BOARD_PIN_NONE)
            finding("slide %u lacks a STEP, DIR or LIM pin", k + 1u);
        add(u, &n, d->step[k], "STEP%u", k + 1u);
        add(u, &n, d->dir[k], "DIR%u", k + 1u);
        add(u, &n, d->lim[k], "LIM%u", k + 1u);
        add(u, &n, d->limh[k], "LIMH%u", k + 1u);
        add(u, &n, d->enable[k], "ENABLE%u", k + 1u);
        if (((d->limh_fitted >> k) & 1u) && d->limh[k] == BOARD_PIN_NONE)
            finding("LIMH%u is fitted but has no pin", k + 1u);
    }
    if (d->enable[0] == BOARD_PIN_NONE)
        finding("no ENABLE pin");
    if (d->estop == BOARD_PIN_NONE)
        finding("no E-STOP pin");
    add(u, &n, d->estop, "E-STOP", 0);
    add(u, &n, d->led, "LED", 0);
    add(u, &n, d->can_rx, "CAN1_RX", 0);
    add(u, &n, d->can_tx, "CAN1_TX", 0);
    add(u, &n, d->boot_tx, "boot line TX", 0);
    for (unsigned i = 0; i < n; ++i) {
        for (unsigned j = i + 1; j < n; ++j)
            if (u[i].pin == u[j].pin)
                finding("two signals on one pin: %s carries %s and %s", name_of(u[i].pin), u[i].what, u[j].what);
        if (!on_package(d->package, u[i].pin))
            finding("pin not on the package: %s on %s, which the STM32F%u in LQFP%u does not have", u[i].what,
                    name_of(u[i].pin), d->part, d->package);
        else if ((u[i].pin >> 4) == 7u && d->hse_hz != 0)
            finding("%s on %s, a pin of the crystal", u[i].what, name_of(u[i].pin));
    }
}

static void check_part(const board_desc *d)
{
    const bool f405 = d->part == 405 && (d->package == 64 || d->package == 100 || d->package == 144);
    const bool f407 = d->part == 407 && (d->package == 100 || d->package == 144);
    if (!f405 && !f407)
        finding("no STM32F%u comes in LQFP%u", d->part, d->package);
    if (sectors_of(d->flash_kib) == 0)
        finding("flash of %u KiB: an STM32F405/407 has 512 or 1024", d->flash_kib);
}

static void check_can_boot(const board_desc *d)
{
    if (d->can_af != 9 || !can1_af9(d->can_rx, true))
        finding("CAN pin without its alternate function: CAN1_RX on %s AF%u (CAN1_RX is AF9 on PA11, PB8, PD0)",
                name_of(d->can_rx), d->can_af);
    if (d->can_af != 9 || !can1_af9(d->can_tx, false))
        finding("CAN pin without its alternate function: CAN1_TX on %s AF%u (CAN1_TX is AF9 on PA12, PB9, PD1)",
                name_of(d->can_tx), d->can_af);
    bool ok = false;
    for (unsigned i = 0; i < sizeof usart_tx / sizeof usart_tx[0]; ++i)
        ok = ok || (usart_tx[i].usart == d->boot_usart && usart_tx[i].af == d->boot_tx_af &&
                    strcmp(usart_tx[i].pin, name_of(d->boot_tx)) == 0);
    if (!ok)
        finding("boot-line TX without its USART alternate function: USART%u_TX on %s AF%u", d->boot_usart,
                name_of(d->boot_tx), d->boot_tx_af);
}

static void check_flash(const board_desc *d)
{
    const unsigned count = sectors_of(d->flash_kib);
    if (count == 0)
        return;
    int app = -1;
    for (unsigned s = 0; s < count; ++s)
        if (sectors[s].addr == d->app_addr)
            app = (int)s;
    if (app < 0)
        finding("application address 0x%08X not sector-aligned: not the start of a flash sector", (unsigned)d->app_addr);
    const unsigned p = d->param_sector;
    if (p + 1u >= count) {
        finding("parameter log in sectors %u and %u: the %u KiB part has sectors 0..%u", p, p + 1u, d->flash_kib,
                count - 1u);
        return;
    }
    if (sectors[p].kib != sectors[p + 1u].kib)
        finding("parameter log sectors %u and %u differ in size", p, p + 1u);
    if (sectors[p].addr < d->app_addr + IMAGE_BUDGET)
        finding("parameter log overlaps the application image: sector %u at 0x%08X, the image from 0x%08X takes up to %u KiB",
                p, (unsigned)sectors[p].addr, (unsigned)d->app_addr, IMAGE_BUDGET / 1024u);
}

static void check_clock(const board_desc *d)
{
    if (d->pll_m < 2 || d->pll_m > 63 || d->pll_n < 50 || d->pll_n > 432 || d->pll_p == 0 || d->pll_q == 0) {
        finding("PLL M/N/P/Q %u/%u/%u/%u outside the PLL's ranges", d->pll_m, d->pll_n, d->pll_p, d->pll_q);
        return;
    }
    const double in = (double)d->hse_hz / d->pll_m, vco = in * d->pll_n;
    if (in < 1e6 || in > 2e6 || vco < 100e6 || vco > 432e6)
        finding("PLL input %.3f MHz (1..2) or VCO %.1f MHz (100..432) out of range", in / 1e6, vco / 1e6);
    if (vco / d->pll_p != 168e6 || vco / d->pll_q != 48e6)
        finding("crystal %u Hz with PLL %u/%u/%u/%u gives SYSCLK %.3f MHz and USB %.3f MHz, not 168 and 48",
                (unsigned)d->hse_hz, d->pll_m, d->pll_n, d->pll_p, d->pll_q, vco / d->pll_p / 1e6, vco / d->pll_q / 1e6);
}

static unsigned check(const board_desc *d)
{
    current = d->name;
    n_findings = 0;
    check_part(d);
    check_pins(d);
    check_can_boot(d);
    check_flash(d);
    check_clock(d);
    return n_findings;
}

int main(int argc, char **argv)
{
    if (argc == 3 && strcmp(argv[1], "--planted") == 0) {
        for (unsigned b = 0; b < board_desc_count; ++b) {
            const board_desc *d = board_descs[b];
            if (strcmp(d->name, argv[2]) != 0)
                continue;
            check(d);
            for (unsigned i = 0; i < n_findings; ++i)
                if (d->planted_expect && strstr(findings[i], d->planted_expect)) {
                    printf("planted %s: found as expected (\"%s\")\n", d->name, d->planted_expect);
                    return 0;
                }
            printf("planted %s: NOT found: no finding names \"%s\"\n", d->name,
                   d->planted_expect ? d->planted_expect : "(no BOARD_PLANTED_EXPECT)");
            return 1;
        }
        fprintf(stderr, "board_check: no planted description '%s'\n", argv[2]);
        return 2;
    }
    if (argc != 1) {
        fprintf(stderr, "usage: board_check | board_check --planted NAME\n");
        return 2;
    }
    unsigned bad = 0;
    for (unsigned b = 0; b < board_desc_count; ++b)
        if (check(board_descs[b]) != 0)
            ++bad;
    printf("%u boards checked, %u with findings\n", board_desc_count, bad);
    return bad ? 1 : 0;
}
