/*
 * STM32F405/407 reset and clock control (RCC, RM0090 section 7).
 *
 * Modelled:
 * - HSI (16 MHz, ready at once), HSE (hse-hz; HSERDY follows HSEON after hse-startup-us, never
 *   with hse-hz 0: a dead crystal), the main PLL (PLLRDY follows PLLON after pll-lock-us, only
 *   while its input is ready and its settings inside RM0090's ranges: VCO input 0.95..2.1 MHz,
 *   VCO output 100..432 MHz, N 50..432, M >= 2; PLLCFGR ignores writes while the PLL runs),
 *   LSI (ready at once).
 * - The system clock switch: SWS follows SW once the selected source is ready; HSE and HSI
 *   cannot be turned off while they feed SYSCLK or the running PLL.
 * - The clock tree: HCLK, PCLK1, PCLK2 and the APB1 and APB2 timer clocks (PCLKx, doubled when
 *   APBx is divided) as QEMU clocks from SW/PLLCFGR/HPRE/PPRE1/PPRE2; the core's clock follows
 *   HCLK.  HSE_RTC, the crystal divided by CFGR's RTCPRE (2..31; 0 and 1: no clock), while HSERDY
 *   (RM0090 7.3.3; TIM11 measures it on channel 1).
 *   More than 168 MHz on HCLK, 42 MHz on PCLK1 or 84 MHz on PCLK2 is reported as a guest error.
 * - The peripheral clock enables (AHB1ENR, APB1ENR, APB2ENR) as output lines: the SoC gates
 *   each peripheral's registers with them (a peripheral with its clock off reads 0 and ignores
 *   writes, as on the part).
 * - Reset flags (CSR): a power-on reset sets PORRSTF, BORRSTF and PINRSTF; a software, watchdog
 *   or pin reset adds SFTRSTF / IWDGRSTF and PINRSTF (the reset drives NRST) to what is there;
 *   only a power-on reset or RMVF clears them.  Every other register returns to its reset value
 *   on any reset.
 * Not modelled: PLLI2S, the clock security system, the ready interrupts (CIR holds what is
 * written), MCO outputs, the peripheral reset registers (they hold what is written), low-power
 * enables (hold what is written), the backup domain beyond holding BDCR, spread spectrum.
 *
 * SPDX-License-Identifier: GPL-2.0-or-later
 */
#include "qemu/osdep.h"
#include "qemu/log.h"
#include "qemu/host-utils.h"
#include "qemu/timer.h"
#include "qapi/error.h"
#include "hw/sysbus.h"
#include "hw/irq.h"
#include "hw/qdev-clock.h"
#include "hw/qdev-properties.h"
#include "sysemu/runstate.h"
#include "tse_f407.h"

OBJECT_DECLARE_SIMPLE_TYPE(Stm32f4RccState, STM32F4_RCC)

#define R_CR 0x00
#define R_PLLCFGR 0x04
#define R_CFGR 0x08
#define R_CIR 0x0C
#define R_AHB1ENR 0x30
#define R_APB1ENR 0x40
#define R_APB2ENR 0x44
#define R_BDCR 0x70
#define R_CSR 0x74
#define NUM_REGS (0x88 / 4)

#define CR_HSION (1u << 0)
#define CR_HSIRDY (1u << 1)
#define CR_HSEON (1u << 16)
#define CR_HSERDY (1u << 17)
#define CR_PLLON (1u << 24)
#define CR_PLLRDY (1u << 25)
#define CR_READ_ONLY (CR_HSIRDY | CR_HSERDY | CR_PLLRDY | (1u << 27) | (0xFFu << 8))

#define PLLCFGR_SRC_HSE (1u << 22)
#define CSR_LSION (1u << 0)
#define CSR_LSIRDY (1u << 1)
#define CSR_RMVF (1u << 24)
#define CSR_BORRSTF (1u << 25)
#define CSR_PINRSTF (1u << 26)
#define CSR_PORRSTF (1u << 27)
#define CSR_SFTRSTF (1u << 28)
#define CSR_IWDGRSTF (1u << 29)
#define CSR_FLAGS (0xFEu << 24)

#define CFGR_RTCPRE(cfgr) (((cfgr) >> 16) & 0x1F)

#define HSI_HZ 16000000u
enum { SRC_HSI, SRC_HSE, SRC_PLL, SRC_NONE };

struct Stm32f4RccState {
    SysBusDevice parent_obj;
    MemoryRegion iomem;
    uint32_t regs[NUM_REGS];
    QEMUTimer *hse_timer, *pll_timer;
    int pending_reset;          /* what the next reset is (RCC_RESET_*) */
    uint32_t warned_hz;         /* the last HCLK a limit warning was given for */
    Clock *hclk, *pclk1, *pclk2, *timclk1, *timclk2, *hse_rtc;
    qemu_irq ahb1en[32], apb1en[32], apb2en[32];
    /* properties */
    uint32_t hse_hz;
    uint32_t hse_startup_us;
    uint32_t pll_lock_us;
};

static uint32_t pll_input_hz(Stm32f4RccState *s)
{
    const uint32_t cfg = s->regs[R_PLLCFGR / 4];
    return (cfg & PLLCFGR_SRC_HSE) ? s->hse_hz : HSI_HZ;
}

/* The PLL's output, or 0 when its settings are outside RM0090's ranges (it never locks). */
static uint64_t pll_out_hz(Stm32f4RccState *s)
{
    const uint32_t cfg = s->regs[R_PLLCFGR / 4];
    const uint32_t m = cfg & 0x3F, n = (cfg >> 6) & 0x1FF, p = 2 * (((cfg >> 16) & 3) + 1);
    const uint64_t in = pll_input_hz(s);
    if (m < 2 || n < 50 || n > 432 || in == 0) {
        return 0;
    }
    const uint64_t vco_in = in / m, vco = vco_in * n;
    if (vco_in < 950000 || vco_in > 2100000 || vco < 100000000 || vco > 432000000) {
        return 0;
    }
    return vco / p;
}

static bool source_ready(Stm32f4RccState *s, int src)
{
    const uint32_t cr = s->regs[R_CR / 4];
    switch (src) {
    case SRC_HSI:
        return cr & CR_HSIRDY;
    case SRC_HSE:
        return cr & CR_HSERDY;
    case SRC_PLL:
        return cr & CR_PLLRDY;
    }
    return false;
}

static uint64_t source_hz(Stm32f4RccState *s, int src)
{
    switch (src) {
    case SRC_HSI:
        return HSI_HZ;
    case SRC_HSE:
        return s->hse_hz;
    case SRC_PLL:
        return pll_out_hz(s);
    }
    return 0;
}

static unsigned ahb_div(uint32_t hpre)
{
    static const unsigned div[8] = {2, 4, 8, 16, 64, 128, 256, 512};
    return (hpre & 8) ? div[hpre & 7] : 1;
}

static unsigned apb_div(uint32_t ppre)
{
    return (ppre & 4) ? 2u << (ppre & 3) : 1;
}

/* Recomputes the tree from SWS and the prescalers and propagates it. */
static void update_clocks(Stm32f4RccState *s)
{
    const uint32_t cfgr = s->regs[R_CFGR / 4];
    const int sws = (cfgr >> 2) & 3;
    const uint64_t sysclk = source_hz(s, sws);
    const uint64_t hclk = sysclk / ahb_div((cfgr >> 4) & 0xF);
    const unsigned d1 = apb_div((cfgr >> 10) & 7), d2 = apb_div((cfgr >> 13) & 7);
    const uint64_t pclk1 = hclk / d1, pclk2 = hclk / d2;
    const uint64_t tim1 = d1 == 1 ? pclk1 : 2 * pclk1, tim2 = d2 == 1 ? pclk2 : 2 * pclk2;
    const uint32_t rtcpre = CFGR_RTCPRE(cfgr);

    if ((hclk > 168000000 || pclk1 > 42000000 || pclk2 > 84000000) && s->warned_hz != hclk) {
        qemu_log_mask(LOG_GUEST_ERROR,
                      "stm32f4-rcc: HCLK %" PRIu64 " Hz, PCLK1 %" PRIu64 " Hz, PCLK2 %" PRIu64
                      " Hz: beyond the part's 168/42/84 MHz\n", hclk, pclk1, pclk2);
        s->warned_hz = hclk;
    }
    clock_update_hz(s->hclk, hclk);
    clock_update_hz(s->pclk1, pclk1);
    clock_update_hz(s->pclk2, pclk2);
    clock_update_hz(s->timclk1, tim1);
    clock_update_hz(s->timclk2, tim2);
    /* HSE_RTC's period exactly (HSE / 31 is not a whole number of Hz): 2^-32 ns units. */
    if ((s->regs[R_CR / 4] & CR_HSERDY) && s->hse_hz && rtcpre >= 2) {
        clock_update(s->hse_rtc, muldiv64(CLOCK_PERIOD_1SEC, rtcpre, s->hse_hz));
    } else {
        clock_update(s->hse_rtc, 0);
    }
}

/* SWS follows SW when the source selected is ready (RM0090 7.3.3); the tree follows SWS. */
static void update_switch(Stm32f4RccState *s)
{
    uint32_t *cfgr = &s->regs[R_CFGR / 4];
    const int sw = *cfgr & 3, sws = (*cfgr >> 2) & 3;
    if (sw != sws && sw != SRC_NONE && source_ready(s, sw)) {
        *cfgr = (*cfgr & ~(3u << 2)) | (uint32_t)sw << 2;
    }
    update_clocks(s);
}

static void hse_ready(void *opaque)
{
    Stm32f4RccState *s = opaque;
    if ((s->regs[R_CR / 4] & CR_HSEON) && s->hse_hz) {
        s->regs[R_CR / 4] |= CR_HSERDY;
        update_switch(s);
    }
}

static bool pll_can_lock(Stm32f4RccState *s)
{
    const bool hse = s->regs[R_PLLCFGR / 4] & PLLCFGR_SRC_HSE;
    return pll_out_hz(s) != 0 && source_ready(s, hse ? SRC_HSE : SRC_HSI);
}

static void pll_ready(void *opaque)
{
    Stm32f4RccState *s = opaque;
    if ((s->regs[R_CR / 4] & CR_PLLON) && pll_can_lock(s)) {
        s->regs[R_CR / 4] |= CR_PLLRDY;
        update_switch(s);
    } else if (s->regs[R_CR / 4] & CR_PLLON) {
        /* Input not ready yet (or settings out of range): try again a lock time later. */
        timer_mod(s->pll_timer, qemu_clock_get_ns(QEMU_CLOCK_VIRTUAL) + s->pll_lock_us * 1000ll);
    }
}

static bool in_use(Stm32f4RccState *s, int src)
{
    const uint32_t cfgr = s->regs[R_CFGR / 4], cr = s->regs[R_CR / 4];
    const int sws = (cfgr >> 2) & 3;
    const bool pll_on = cr & CR_PLLON;
    const int pll_src = (s->regs[R_PLLCFGR / 4] & PLLCFGR_SRC_HSE) ? SRC_HSE : SRC_HSI;
    return sws == src || (pll_on && pll_src == src && src != SRC_PLL);
}

static void write_cr(Stm32f4RccState *s, uint32_t v)
{
    uint32_t *cr = &s->regs[R_CR / 4];
    const uint32_t old = *cr;
    const int64_t now = qemu_clock_get_ns(QEMU_CLOCK_VIRTUAL);

    /* An oscillator feeding SYSCLK (directly or through the running PLL) stays on. */
    if (!(v & CR_HSION) && in_use(s, SRC_HSI)) {
        v |= CR_HSION;
    }
    if (!(v & CR_HSEON) && in_use(s, SRC_HSE)) {
        v |= CR_HSEON;
    }
    if (!(v & CR_PLLON) && ((s->regs[R_CFGR / 4] >> 2) & 3) == SRC_PLL) {
        v |= CR_PLLON;
    }
    *cr = (old & CR_READ_ONLY) | (v & ~CR_READ_ONLY);

    *cr = (*cr & CR_HSION) ? (*cr | CR_HSIRDY) : (*cr & ~CR_HSIRDY);
    if ((v & CR_HSEON) && !(old & CR_HSEON)) {
        timer_mod(s->hse_timer, now + s->hse_startup_us * 1000ll);
    } else if (!(v & CR_HSEON)) {
        timer_del(s->hse_timer);
        *cr &= ~CR_HSERDY;
    }
    if ((v & CR_PLLON) && !(old & CR_PLLON)) {
        timer_mod(s->pll_timer, now + s->pll_lock_us * 1000ll);
    } else if (!(v & CR_PLLON)) {
        timer_del(s->pll_timer);
        *cr &= ~CR_PLLRDY;
    }
    update_switch(s);
}

static void set_lines(qemu_irq *lines, uint32_t old, uint32_t v)
{
    for (int i = 0; i < 32; ++i) {
        if (((old ^ v) >> i) & 1) {
            qemu_set_irq(lines[i], (v >> i) & 1);
        }
    }
}

static uint64_t rcc_read(void *opaque, hwaddr addr, unsigned size)
{
    Stm32f4RccState *s = opaque;
    return addr < NUM_REGS * 4 ? s->regs[addr / 4] : 0;
}

static void rcc_write(void *opaque, hwaddr addr, uint64_t val, unsigned size)
{
    Stm32f4RccState *s = opaque;
    const uint32_t v = val;
    uint32_t *r = &s->regs[addr / 4];
    const uint32_t old = *r;

    if (addr >= NUM_REGS * 4) {
        qemu_log_mask(LOG_GUEST_ERROR, "stm32f4-rcc: write to 0x%" HWADDR_PRIx "\n", addr);
        return;
    }
    switch (addr) {
    case R_CR:
        write_cr(s, v);
        return;
    case R_PLLCFGR:
        if (s->regs[R_CR / 4] & CR_PLLON) {
            qemu_log_mask(LOG_GUEST_ERROR, "stm32f4-rcc: PLLCFGR written while the PLL is on: ignored\n");
            return;
        }
        *r = v & 0x0F437FFF;
        return;
    case R_CFGR:
        *r = (old & (3u << 2)) | (v & ~(3u << 2));
        update_switch(s);
        return;
    case R_AHB1ENR:
        *r = v;
        set_lines(s->ahb1en, old, v);
        return;
    case R_APB1ENR:
        *r = v;
        set_lines(s->apb1en, old, v);
        return;
    case R_APB2ENR:
        *r = v;
        set_lines(s->apb2en, old, v);
        return;
    case R_CSR:
        *r = (old & CSR_FLAGS) | (v & CSR_LSION);
        *r = (*r & CSR_LSION) ? (*r | CSR_LSIRDY) : (*r & ~CSR_LSIRDY);
        if (v & CSR_RMVF) {
            *r &= ~CSR_FLAGS;
        }
        return;
    default:
        *r = v;
    }
}

static const MemoryRegionOps rcc_ops = {
    .read = rcc_read,
    .write = rcc_write,
    .endianness = DEVICE_LITTLE_ENDIAN,
    .valid = { .min_access_size = 1, .max_access_size = 4 },
    .impl = { .min_access_size = 4, .max_access_size = 4 },
};

/* A reset request: remember its kind (the strongest of those pending) and reset the system. */
static void reset_request(void *opaque, int kind, int level)
{
    Stm32f4RccState *s = opaque;
    static const int rank[RCC_RESET_N] = {
        [RCC_RESET_PIN] = 0, [RCC_RESET_SOFTWARE] = 1, [RCC_RESET_IWDG] = 2,
        [RCC_RESET_POWER_ON] = 3,
    };
    if (!level) {
        return;
    }
    if (rank[kind] >= rank[s->pending_reset]) {
        s->pending_reset = kind;
    }
    qemu_system_reset_request(SHUTDOWN_CAUSE_GUEST_RESET);
}

static void rcc_reset(DeviceState *dev)
{
    Stm32f4RccState *s = STM32F4_RCC(dev);
    uint32_t flags = s->regs[R_CSR / 4] & CSR_FLAGS;
    const uint32_t bdcr = s->regs[R_BDCR / 4];

    switch (s->pending_reset) {
    case RCC_RESET_POWER_ON:
        flags = CSR_PORRSTF | CSR_BORRSTF | CSR_PINRSTF;
        break;
    case RCC_RESET_SOFTWARE:
        flags |= CSR_SFTRSTF | CSR_PINRSTF;
        break;
    case RCC_RESET_IWDG:
        flags |= CSR_IWDGRSTF | CSR_PINRSTF;
        break;
    default:
        flags |= CSR_PINRSTF;
    }
    /* A reset that no model asked for (the monitor's system_reset, a debugger) is NRST's. */
    const bool power_on = s->pending_reset == RCC_RESET_POWER_ON;
    s->pending_reset = RCC_RESET_PIN;

    timer_del(s->hse_timer);
    timer_del(s->pll_timer);
    memset(s->regs, 0, sizeof s->regs);
    s->regs[R_CR / 4] = 0x00000083;
    s->regs[R_PLLCFGR / 4] = 0x24003010;
    s->regs[R_AHB1ENR / 4] = 0x00100000;
    s->regs[0x50 / 4] = 0x7E6791FF;
    s->regs[0x54 / 4] = 0x000000F1;
    s->regs[0x58 / 4] = 0x00000001;
    s->regs[0x60 / 4] = 0x36FEC9FF;
    s->regs[0x64 / 4] = 0x00075F33;
    s->regs[R_BDCR / 4] = power_on ? 0 : bdcr;
    s->regs[R_CSR / 4] = flags;
    s->regs[0x84 / 4] = 0x20003000; /* PLLI2SCFGR */
    s->warned_hz = 0;
    for (int i = 0; i < 32; ++i) {
        qemu_set_irq(s->ahb1en[i], (0x00100000u >> i) & 1);
        qemu_set_irq(s->apb1en[i], 0);
        qemu_set_irq(s->apb2en[i], 0);
    }
    update_clocks(s);
}

static void rcc_init(Object *obj)
{
    Stm32f4RccState *s = STM32F4_RCC(obj);
    DeviceState *dev = DEVICE(obj);

    memory_region_init_io(&s->iomem, obj, &rcc_ops, s, "stm32f4-rcc", 0x400);
    sysbus_init_mmio(SYS_BUS_DEVICE(obj), &s->iomem);
    s->hclk = qdev_init_clock_out(dev, RCC_CLK_HCLK);
    s->pclk1 = qdev_init_clock_out(dev, RCC_CLK_PCLK1);
    s->pclk2 = qdev_init_clock_out(dev, RCC_CLK_PCLK2);
    s->timclk1 = qdev_init_clock_out(dev, RCC_CLK_TIMCLK1);
    s->timclk2 = qdev_init_clock_out(dev, RCC_CLK_TIMCLK2);
    s->hse_rtc = qdev_init_clock_out(dev, RCC_CLK_HSE_RTC);
    qdev_init_gpio_out_named(dev, s->ahb1en, RCC_GPIO_AHB1EN, 32);
    qdev_init_gpio_out_named(dev, s->apb1en, RCC_GPIO_APB1EN, 32);
    qdev_init_gpio_out_named(dev, s->apb2en, RCC_GPIO_APB2EN, 32);
    qdev_init_gpio_in_named(dev, reset_request, RCC_GPIO_RESET, RCC_RESET_N);
    s->pending_reset = RCC_RESET_POWER_ON; /* QEMU's first reset is the power-on */
}

static void rcc_realize(DeviceState *dev, Error **errp)
{
    Stm32f4RccState *s = STM32F4_RCC(dev);
    s->hse_timer = timer_new_ns(QEMU_CLOCK_VIRTUAL, hse_ready, s);
    s->pll_timer = timer_new_ns(QEMU_CLOCK_VIRTUAL, pll_ready, s);
}

static Property rcc_properties[] = {
    DEFINE_PROP_UINT32("hse-hz", Stm32f4RccState, hse_hz, 8000000),
    DEFINE_PROP_UINT32("hse-startup-us", Stm32f4RccState, hse_startup_us, 2000),
    DEFINE_PROP_UINT32("pll-lock-us", Stm32f4RccState, pll_lock_us, 100),
    DEFINE_PROP_END_OF_LIST(),
};

static void rcc_class_init(ObjectClass *klass, void *data)
{
    DeviceClass *dc = DEVICE_CLASS(klass);
    dc->realize = rcc_realize;
    dc->reset = rcc_reset;
    device_class_set_props(dc, rcc_properties);
}

static const TypeInfo rcc_info = {
    .name = TYPE_STM32F4_RCC,
    .parent = TYPE_SYS_BUS_DEVICE,
    .instance_size = sizeof(Stm32f4RccState),
    .instance_init = rcc_init,
    .class_init = rcc_class_init,
};

static void rcc_register_types(void)
{
    type_register_static(&rcc_info);
}

type_init(rcc_register_types)
