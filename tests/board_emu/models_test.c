/* The emulator's device models against the reference manual (RM0090), from the core's side: a
 * test image for the tse-f407 machine (not the board: it pokes registers into states the
 * firmware never uses).  Every expected value below is the manual's, not the model's.
 * Cases run on the reset clocks (HSI, 16 MHz) except the last, which builds the PLL. */
#include <stdbool.h>
#include <stdint.h>

#include "hal_stm32f4/regs_can.h"
#include "hal_stm32f4/regs_core.h"
#include "hal_stm32f4/regs_flash.h"
#include "hal_stm32f4/regs_gpio.h"
#include "hal_stm32f4/regs_misc.h"
#include "hal_stm32f4/regs_rcc.h"
#include "hal_stm32f4/regs_tim.h"
#include "target_test.h"

#define GPIOD ((tse_gpio_regs *)0x40020C00u)
#define GPIOE ((tse_gpio_regs *)0x40021000u)
#define AHB1ENR_GPIOD (1u << 3)
#define AHB1ENR_GPIOE (1u << 4)

/* ---- time: TIM5 at 1 MHz from the 16 MHz HSI ---- */

static void clock_us_start(void)
{
    TSE_RCC->APB1ENR |= RCC_APB1ENR_TIM5;
    TSE_TIM5->CR1 = 0;
    TSE_TIM5->PSC = 15;
    TSE_TIM5->ARR = 0xFFFFFFFFu;
    TSE_TIM5->EGR = TIM_EGR_UG;
    TSE_TIM5->SR = 0;
    TSE_TIM5->CR1 = TIM_CR1_CEN;
}

static uint32_t now_us(void)
{
    return TSE_TIM5->CNT;
}

/* Waits until (*r & mask) == want, at most limit_us; returns the microseconds it took, or
 * UINT32_MAX when it never came. */
static uint32_t wait_for(volatile uint32_t *r, uint32_t mask, uint32_t want, uint32_t limit_us)
{
    const uint32_t t0 = now_us();
    while ((*r & mask) != want)
        if (now_us() - t0 > limit_us)
            return UINT32_MAX;
    return now_us() - t0;
}

static void spin_us(uint32_t n)
{
    const uint32_t t0 = now_us();
    while (now_us() - t0 < n)
        ;
}

/* ---- a bus fault taken and stepped over (a 16-bit store, see store16) ---- */

static volatile uint32_t bus_faults;

void BusFault_Handler(void);
__attribute__((naked)) void BusFault_Handler(void)
{
    __asm__ volatile("tst lr, #4\n\t"
                     "ite eq\n\t"
                     "mrseq r0, msp\n\t"
                     "mrsne r0, psp\n\t"
                     "ldr r1, [r0, #24]\n\t" /* the stacked pc: the faulting store */
                     "adds r1, #2\n\t"
                     "str r1, [r0, #24]\n\t"
                     "ldr r1, =bus_faults\n\t"
                     "ldr r2, [r1]\n\t"
                     "adds r2, #1\n\t"
                     "str r2, [r1]\n\t"
                     "ldr r1, =0xE000ED28\n\t" /* CFSR: clear what it recorded */
                     "ldr r2, [r1]\n\t"
                     "str r2, [r1]\n\t"
                     "bx lr\n");
}

/* A word store in a 16-bit instruction (low registers), for BusFault_Handler to step over. */
static void store16(volatile uint32_t *addr, uint32_t value)
{
    __asm__ volatile("str %1, [%0]" ::"l"(addr), "l"(value) : "memory");
}

/* ---- RCC ---- */

static void rcc_reset_state(void)
{
    /* RM0090 7.3.21: a power-on reset sets PORRSTF, BORRSTF and PINRSTF. */
    const uint32_t csr = TSE_RCC->CSR;
    TT_CHECKF((csr & (RCC_CSR_PORRSTF | RCC_CSR_PINRSTF)) == (RCC_CSR_PORRSTF | RCC_CSR_PINRSTF), "CSR %08lx\n",
              (unsigned long)csr);
    TT_CHECK((csr & (RCC_CSR_IWDGRSTF | RCC_CSR_SFTRSTF)) == 0);
    TSE_RCC->CSR |= RCC_CSR_RMVF;
    TT_CHECK((TSE_RCC->CSR & (0xFEu << 24)) == 0);
    TT_CHECK(TSE_RCC->CR & RCC_CR_HSIRDY);
    TT_CHECK((TSE_RCC->CFGR & RCC_CFGR_SWS_MASK) == 0); /* the HSI */
    TT_CHECK(TSE_RCC->PLLCFGR == 0x24003010u);
}

static void rcc_clock_gates(void)
{
    /* A peripheral whose clock is off reads 0 and ignores writes. */
    TSE_RCC->AHB1ENR &= ~AHB1ENR_GPIOD;
    GPIOD->MODER = 0x5u;
    TT_CHECK(GPIOD->MODER == 0);
    TSE_RCC->AHB1ENR |= AHB1ENR_GPIOD;
    GPIOD->MODER = 0x5u;
    TT_CHECK(GPIOD->MODER == 0x5u);
    TSE_RCC->AHB1ENR &= ~AHB1ENR_GPIOD;
    TT_CHECK(GPIOD->MODER == 0);
}

/* ---- GPIO ---- */

static void gpio_pins(void)
{
    TSE_RCC->AHB1ENR |= AHB1ENR_GPIOE;
    GPIOE->MODER = 0;
    GPIOE->PUPDR = 1u << 0; /* pin 0 pull-up */
    TT_CHECK(GPIOE->IDR & 1u);
    GPIOE->PUPDR = 2u << 0; /* pull-down */
    TT_CHECK(!(GPIOE->IDR & 1u));
    /* BSRR: with both bits of a pin written, set wins (RM0090 8.4.7). */
    GPIOE->MODER = 1u << 2;
    GPIOE->BSRR = (1u << 1) | (1u << 17);
    TT_CHECK(GPIOE->ODR & 2u);
    TT_CHECK(GPIOE->IDR & 2u);
    GPIOE->BSRR = 1u << 17;
    TT_CHECK(!(GPIOE->ODR & 2u));
    TT_CHECK(GPIOE->BSRR == 0); /* write-only */
}

static void gpio_lock(void)
{
    TSE_RCC->AHB1ENR |= AHB1ENR_GPIOE;
    GPIOE->MODER = 0;
    /* RM0090 8.4.8: LCKK=1, LCKK=0, LCKK=1 with the same LCK bits, then a read. */
    const uint32_t lckk = 1u << 16, pin = 1u << 2;
    GPIOE->LCKR = lckk | pin;
    GPIOE->LCKR = pin;
    GPIOE->LCKR = lckk | pin;
    (void)GPIOE->LCKR;
    TT_CHECK(GPIOE->LCKR & lckk);
    GPIOE->MODER = (1u << 4) | (1u << 6); /* pins 2 and 3 to output */
    TT_CHECKF(GPIOE->MODER == (1u << 6), "MODER %08lx\n", (unsigned long)GPIOE->MODER);
}

/* ---- EXTI through SYSCFG ---- */

static void exti_edges(void)
{
    TSE_RCC->AHB1ENR |= AHB1ENR_GPIOE;
    TSE_RCC->APB2ENR |= RCC_APB2ENR_SYSCFG;
    /* Software trigger: only through the mask. */
    TSE_EXTI->IMR = 0;
    TSE_EXTI->SWIER = 1u << 1;
    TT_CHECK(!(TSE_EXTI->PR & (1u << 1)));
    TSE_EXTI->SWIER = 0;
    TSE_EXTI->PR = 1u << 1;
    TSE_EXTI->IMR = 1u << 1;
    TSE_EXTI->SWIER = 1u << 1;
    TT_CHECK(TSE_EXTI->PR & (1u << 1));
    TSE_EXTI->PR = 1u << 1;
    TT_CHECK(!(TSE_EXTI->PR & (1u << 1)));
    TT_CHECK(!(TSE_EXTI->SWIER & (1u << 1)));
    /* PE3 on line 3 (EXTICR1 bits 15:12 = 4, port E), rising edge only. */
    GPIOE->MODER &= ~(3u << 6);
    GPIOE->PUPDR = (GPIOE->PUPDR & ~(3u << 6)) | 2u << 6; /* low */
    TSE_SYSCFG->EXTICR[0] = (TSE_SYSCFG->EXTICR[0] & ~(0xFu << 12)) | 4u << 12;
    TSE_EXTI->RTSR = 1u << 3;
    TSE_EXTI->FTSR = 0;
    TSE_EXTI->IMR = 1u << 3;
    TSE_EXTI->PR = 1u << 3;
    GPIOE->PUPDR = (GPIOE->PUPDR & ~(3u << 6)) | 1u << 6; /* rises */
    TT_CHECK(TSE_EXTI->PR & (1u << 3));
    TSE_EXTI->PR = 1u << 3;
    GPIOE->PUPDR = (GPIOE->PUPDR & ~(3u << 6)) | 2u << 6; /* falls: not selected */
    TT_CHECK(!(TSE_EXTI->PR & (1u << 3)));
    /* A line routed from another port does not see PE3. */
    TSE_SYSCFG->EXTICR[0] &= ~(0xFu << 12);
    TSE_EXTI->PR = 1u << 3;
    GPIOE->PUPDR = (GPIOE->PUPDR & ~(3u << 6)) | 1u << 6;
    TT_CHECK(!(TSE_EXTI->PR & (1u << 3)));
    TSE_EXTI->IMR = 0;
}

/* ---- timers ---- */

static void tim_update_generation(void)
{
    TSE_RCC->APB1ENR |= RCC_APB1ENR_TIM3;
    TSE_TIM3->CR1 = 0;
    TSE_TIM3->PSC = 0;
    TSE_TIM3->ARR = 1000;
    TSE_TIM3->SR = 0;
    TSE_TIM3->EGR = TIM_EGR_UG; /* URS clear: UG sets UIF */
    TT_CHECK(TSE_TIM3->SR & TIM_SR_UIF);
    TSE_TIM3->SR = 0;
    TSE_TIM3->CR1 = TIM_CR1_URS;
    TSE_TIM3->EGR = TIM_EGR_UG; /* URS: only an overflow sets it */
    TT_CHECK(!(TSE_TIM3->SR & TIM_SR_UIF));
    TT_CHECK(TSE_TIM3->CNT == 0);
}

static void tim_one_pulse(void)
{
    TSE_RCC->APB1ENR |= RCC_APB1ENR_TIM3;
    TSE_TIM3->CR1 = 0;
    TSE_TIM3->PSC = 15; /* 1 MHz */
    TSE_TIM3->EGR = TIM_EGR_UG;
    TSE_TIM3->ARR = 99; /* 100 us */
    TSE_TIM3->SR = 0;
    TSE_TIM3->CNT = 0;
    TSE_TIM3->CR1 = TIM_CR1_OPM | TIM_CR1_URS | TIM_CR1_CEN;
    const uint32_t took = wait_for(&TSE_TIM3->SR, TIM_SR_UIF, TIM_SR_UIF, 1000);
    TT_CHECKF(took >= 95 && took <= 110, "update after %lu us\n", (unsigned long)took);
    TT_CHECK(!(TSE_TIM3->CR1 & TIM_CR1_CEN)); /* one pulse: stopped at the update */
    spin_us(50);
    TT_CHECK(TSE_TIM3->CNT == 0);
}

static void tim_prescaler_preload(void)
{
    TSE_RCC->APB1ENR |= RCC_APB1ENR_TIM3;
    TSE_TIM3->CR1 = 0;
    TSE_TIM3->PSC = 0;
    TSE_TIM3->ARR = 0xFFFF;
    TSE_TIM3->EGR = TIM_EGR_UG;
    TSE_TIM3->CR1 = TIM_CR1_CEN;
    TSE_TIM3->PSC = 15; /* preloaded: 16 MHz until the next update event */
    uint32_t c0 = TSE_TIM3->CNT;
    spin_us(100);
    uint32_t n = (TSE_TIM3->CNT - c0) & 0xFFFF;
    TT_CHECKF(n > 1400 && n < 1800, "%lu counts in 100 us before the update\n", (unsigned long)n);
    TSE_TIM3->EGR = TIM_EGR_UG;
    c0 = TSE_TIM3->CNT;
    spin_us(100);
    n = (TSE_TIM3->CNT - c0) & 0xFFFF;
    TT_CHECKF(n >= 95 && n <= 110, "%lu counts in 100 us after it\n", (unsigned long)n);
    /* The counter wraps at ARR (from below it: a counter already above a new ARR runs on to
     * 0xFFFF first). */
    TSE_TIM3->ARR = 9;
    TSE_TIM3->EGR = TIM_EGR_UG;
    uint32_t top = 0;
    for (int i = 0; i < 200; ++i) {
        const uint32_t c = TSE_TIM3->CNT;
        top = c > top ? c : top;
    }
    TT_CHECKF(top == 9, "highest count %lu with ARR 9\n", (unsigned long)top);
    TSE_TIM3->CR1 = 0;
}

/* ---- IWDG (never started here: nothing but a reset would stop it) ---- */

static void iwdg_write_access(void)
{
    TSE_IWDG->PR = 3; /* without 0x5555: ignored */
    TT_CHECK(TSE_IWDG->PR == 0);
    TSE_IWDG->KR = IWDG_KEY_UNLOCK;
    TSE_IWDG->PR = 3;
    TT_CHECK(TSE_IWDG->SR & IWDG_SR_PVU);
    /* Up to 5 periods of the 32 kHz LSI (RM0090 19.4.4): about 160 us. */
    const uint32_t took = wait_for(&TSE_IWDG->SR, IWDG_SR_PVU, 0, 2000);
    TT_CHECKF(took >= 100 && took <= 400, "PVU cleared after %lu us\n", (unsigned long)took);
    TT_CHECK(TSE_IWDG->PR == 3);
}

/* ---- flash ---- */

#define SECTOR11 ((volatile uint32_t *)0x080E0000u)

static void flash_unlock(void)
{
    TSE_FLASH->KEYR = FLASH_KEY1;
    TSE_FLASH->KEYR = FLASH_KEY2;
}

static void flash_program(void)
{
    TT_CHECK(TSE_FLASH->CR & FLASH_CR_LOCK);
    flash_unlock();
    TT_CHECK(!(TSE_FLASH->CR & FLASH_CR_LOCK));
    TSE_FLASH->SR = 0xF3;
    TSE_FLASH->CR = FLASH_CR_PSIZE_X32 | FLASH_CR_PG;
    SECTOR11[1] = 0x0F0F0F0Fu;
    const uint32_t took = wait_for(&TSE_FLASH->SR, FLASH_SR_BSY, 0, 1000);
    TT_CHECKF(took != UINT32_MAX && took >= 5, "programming took %lu us\n", (unsigned long)took);
    TT_CHECK(TSE_FLASH->SR & FLASH_SR_EOP);
    TT_CHECK(SECTOR11[1] == 0x0F0F0F0Fu);
    /* Programming only clears bits: over a word not erased, old AND new. */
    SECTOR11[1] = 0xF0F0F0FFu;
    wait_for(&TSE_FLASH->SR, FLASH_SR_BSY, 0, 1000);
    TT_CHECKF(SECTOR11[1] == 0x0000000Fu, "%08lx\n", (unsigned long)SECTOR11[1]);
    /* A byte at x32 parallelism: PGPERR, nothing written. */
    *(volatile uint8_t *)&SECTOR11[2] = 0x12;
    TT_CHECK(TSE_FLASH->SR & FLASH_SR_PGPERR);
    TT_CHECK(SECTOR11[2] == 0xFFFFFFFFu);
    TSE_FLASH->SR = 0xF3;
    /* Without PG: a sequence error. */
    TSE_FLASH->CR = FLASH_CR_PSIZE_X32;
    SECTOR11[3] = 0x12345678u;
    TT_CHECK(TSE_FLASH->SR & FLASH_SR_PGSERR);
    TT_CHECK(SECTOR11[3] == 0xFFFFFFFFu);
    TSE_FLASH->SR = 0xF3;
    TSE_FLASH->CR = FLASH_CR_LOCK;
}

static void flash_erase(void)
{
    flash_unlock();
    TSE_FLASH->SR = 0xF3;
    TSE_FLASH->CR = FLASH_CR_PSIZE_X32 | FLASH_CR_SER | FLASH_CR_SNB(11);
    TSE_FLASH->CR |= FLASH_CR_STRT;
    TT_CHECK(TSE_FLASH->SR & FLASH_SR_BSY);
    /* A 128 KiB sector at x32: 1 s typical, 2 s at most (datasheet). */
    const uint32_t took = wait_for(&TSE_FLASH->SR, FLASH_SR_BSY, 0, 3000000);
    TT_CHECKF(took >= 500000 && took != UINT32_MAX, "erase took %lu us\n", (unsigned long)took);
    TT_CHECK(TSE_FLASH->SR & FLASH_SR_EOP);
    TT_CHECK(SECTOR11[1] == 0xFFFFFFFFu);
    TT_CHECK(SECTOR11[0x7FFF] == 0xFFFFFFFFu);
    TSE_FLASH->CR = FLASH_CR_LOCK;
}

static void flash_wrong_key(void)
{
    TT_CHECK(TSE_FLASH->CR & FLASH_CR_LOCK);
    const uint32_t before = bus_faults;
    store16(&TSE_FLASH->KEYR, 0x12345678u);
    TT_CHECKF(bus_faults == before + 1, "%lu bus faults\n", (unsigned long)(bus_faults - before));
    /* Locked until reset: the right keys no longer unlock it (RM0090 3.5.1). */
    store16(&TSE_FLASH->KEYR, FLASH_KEY1);
    store16(&TSE_FLASH->KEYR, FLASH_KEY2);
    TT_CHECK(TSE_FLASH->CR & FLASH_CR_LOCK);
}

/* ---- bxCAN in loop-back and silent mode: the hot self-test of RM0090 32.5.3 ---- */

#define CAN TSE_CAN1

static void can_send(unsigned m, uint32_t id, uint8_t tag)
{
    CAN->TX[m].TDTR = 8;
    CAN->TX[m].TDLR = 0x03020100u | tag;
    CAN->TX[m].TDHR = 0x07060504u;
    CAN->TX[m].TIR = id << CAN_IR_STID_SHIFT | CAN_TIR_TXRQ;
}

static uint32_t fifo_id(unsigned f)
{
    return CAN->RX[f].RIR >> CAN_IR_STID_SHIFT;
}

static void fifo_release(unsigned f)
{
    volatile uint32_t *rfr = f ? &CAN->RF1R : &CAN->RF0R;
    *rfr = CAN_RFR_RFOM;
}

static unsigned fmp(unsigned f)
{
    return (f ? CAN->RF1R : CAN->RF0R) & CAN_RFR_FMP_MASK;
}

static bool enter_init(void)
{
    CAN->MCR = CAN->MCR | CAN_MCR_INRQ;
    return wait_for(&CAN->MSR, CAN_MSR_INAK, CAN_MSR_INAK, 1000) != UINT32_MAX;
}

static bool leave_init(uint32_t mcr)
{
    CAN->MCR = mcr;
    return wait_for(&CAN->MSR, CAN_MSR_INAK, 0, 1000) != UINT32_MAX;
}

static void can_modes_and_filters(void)
{
    TSE_RCC->APB1ENR |= RCC_APB1ENR_CAN1;
    TT_CHECK(CAN->MCR == 0x00010002u);
    TT_CHECK((CAN->MSR & (CAN_MSR_SLAK | CAN_MSR_INAK)) == CAN_MSR_SLAK); /* asleep */
    CAN->MCR = CAN_MCR_INRQ;
    TT_CHECK(wait_for(&CAN->MSR, CAN_MSR_INAK | CAN_MSR_SLAK, CAN_MSR_INAK, 1000) != UINT32_MAX);
    /* 500 kbit/s from 16 MHz: 32 clocks a bit, prescaler 2, 1 + 13 + 2 quanta. */
    const uint32_t btr = CAN_BTR_LBKM | CAN_BTR_SILM | (2u - 1u) | (13u - 1u) << CAN_BTR_TS1_SHIFT |
                         (2u - 1u) << CAN_BTR_TS2_SHIFT;
    CAN->BTR = btr;
    TT_CHECK(CAN->BTR == btr);
    /* Bank 0: 32-bit list of 0x100 and 0x200, FIFO 0 (match indexes 0, 1).  Bank 1: 16-bit
     * masks to FIFO 1: 0x300 exactly (index 0), and 0x4xx (index 1). */
    CAN->FMR |= CAN_FMR_FINIT;
    CAN->FA1R = 0;
    CAN->FS1R = 1u << 0;
    CAN->FM1R = 1u << 0;
    CAN->FFA1R = 1u << 1;
    CAN->FB[0].FR1 = 0x100u << 21;
    CAN->FB[0].FR2 = 0x200u << 21;
    CAN->FB[1].FR1 = (0x7FFu << 5 | CAN_F16_RTR | CAN_F16_IDE) << 16 | 0x300u << 5;
    CAN->FB[1].FR2 = (0x700u << 5 | CAN_F16_RTR | CAN_F16_IDE) << 16 | 0x400u << 5;
    CAN->FA1R = 3;
    CAN->FMR &= ~CAN_FMR_FINIT;
    /* Three frames queued in initialisation, sent by identifier (not by mailbox) when the
     * controller joins. */
    can_send(0, 0x200, 0xA0);
    can_send(1, 0x300, 0xA1);
    can_send(2, 0x100, 0xA2);
    spin_us(500);
    TT_CHECK((CAN->TSR & CAN_TSR_TME_ALL) == 0); /* nothing leaves in initialisation */
    TT_CHECK(leave_init(0));
    CAN->BTR = 0; /* outside initialisation: ignored */
    TT_CHECK(CAN->BTR == btr);
    TT_CHECK(wait_for(&CAN->TSR, CAN_TSR_TME_ALL, CAN_TSR_TME_ALL, 5000) != UINT32_MAX);
    const uint32_t done = CAN_TSR_RQCP(0) | CAN_TSR_TXOK(0) | CAN_TSR_RQCP(1) | CAN_TSR_TXOK(1) |
                          CAN_TSR_RQCP(2) | CAN_TSR_TXOK(2);
    TT_CHECK((CAN->TSR & done) == done);
    CAN->TSR = CAN_TSR_RQCP_ALL;
    TT_CHECK((CAN->TSR & done) == 0);
    TT_CHECK(fmp(0) == 2 && fmp(1) == 1);
    TT_CHECKF(fifo_id(0) == 0x100, "first in FIFO 0: %03lx\n", (unsigned long)fifo_id(0));
    TT_CHECK(((CAN->RX[0].RDTR >> 8) & 0xFF) == 0); /* FMI */
    TT_CHECK((CAN->RX[0].RDTR & 0xF) == 8);
    TT_CHECK(CAN->RX[0].RDLR == 0x030201A2u && CAN->RX[0].RDHR == 0x07060504u);
    fifo_release(0);
    TT_CHECK(fifo_id(0) == 0x200 && ((CAN->RX[0].RDTR >> 8) & 0xFF) == 1);
    fifo_release(0);
    TT_CHECK(fmp(0) == 0);
    TT_CHECK(fifo_id(1) == 0x300 && ((CAN->RX[1].RDTR >> 8) & 0xFF) == 0);
    fifo_release(1);
    /* 0x4A5 through bank 1's second mask; 0x555 through nothing. */
    can_send(0, 0x4A5, 0xB0);
    can_send(1, 0x555, 0xB1);
    TT_CHECK(wait_for(&CAN->TSR, CAN_TSR_TME_ALL, CAN_TSR_TME_ALL, 5000) != UINT32_MAX);
    TT_CHECK(fmp(0) == 0 && fmp(1) == 1);
    TT_CHECK(fifo_id(1) == 0x4A5 && ((CAN->RX[1].RDTR >> 8) & 0xFF) == 1);
    fifo_release(1);
    CAN->TSR = CAN_TSR_RQCP_ALL;
}

static void can_request_order(void)
{
    /* TXFP: in the order requested, not by identifier. */
    TT_CHECK(enter_init());
    can_send(2, 0x200, 0xC0);
    can_send(0, 0x100, 0xC1);
    TT_CHECK(leave_init(CAN_MCR_TXFP));
    TT_CHECK(wait_for(&CAN->TSR, CAN_TSR_TME_ALL, CAN_TSR_TME_ALL, 5000) != UINT32_MAX);
    TT_CHECK(fmp(0) == 2);
    TT_CHECKF(fifo_id(0) == 0x200, "first %03lx\n", (unsigned long)fifo_id(0));
    fifo_release(0);
    TT_CHECK(fifo_id(0) == 0x100);
    fifo_release(0);
    CAN->TSR = CAN_TSR_RQCP_ALL;
}

/* Four frames into a FIFO of three. */
static void can_fill_four(void)
{
    for (uint8_t k = 0; k < 4; ++k) {
        can_send(0, 0x100, (uint8_t)(0xD0 + k));
        wait_for(&CAN->TSR, CAN_TSR_TME(0), CAN_TSR_TME(0), 5000);
    }
    CAN->TSR = CAN_TSR_RQCP_ALL;
}

static void can_overrun(void)
{
    /* Not locked: the newest frame replaces the last one stored (RM0090 32.7.5). */
    can_fill_four();
    TT_CHECK(fmp(0) == 3);
    TT_CHECK(CAN->RF0R & CAN_RFR_FOVR);
    TT_CHECK(CAN->RF0R & CAN_RFR_FULL);
    const uint8_t want_open[3] = {0xD0, 0xD1, 0xD3};
    for (unsigned i = 0; i < 3; ++i) {
        TT_CHECKF((CAN->RX[0].RDLR & 0xFF) == want_open[i], "frame %u: %02lx\n", i,
                  (unsigned long)(CAN->RX[0].RDLR & 0xFF));
        fifo_release(0);
    }
    CAN->RF0R = CAN_RFR_FOVR | CAN_RFR_FULL;
    TT_CHECK((CAN->RF0R & (CAN_RFR_FOVR | CAN_RFR_FULL | CAN_RFR_FMP_MASK)) == 0);
    /* Locked (RFLM): the incoming frame is dropped. */
    TT_CHECK(enter_init());
    TT_CHECK(leave_init(CAN_MCR_RFLM));
    can_fill_four();
    const uint8_t want_locked[3] = {0xD0, 0xD1, 0xD2};
    for (unsigned i = 0; i < 3; ++i) {
        TT_CHECK((CAN->RX[0].RDLR & 0xFF) == want_locked[i]);
        fifo_release(0);
    }
    CAN->RF0R = CAN_RFR_FOVR | CAN_RFR_FULL;
}

static void can_sleep(void)
{
    CAN->MCR = CAN_MCR_SLEEP;
    TT_CHECK(wait_for(&CAN->MSR, CAN_MSR_SLAK | CAN_MSR_INAK, CAN_MSR_SLAK, 1000) != UINT32_MAX);
    TT_CHECK(CAN->MSR & CAN_MSR_SLAKI);
    CAN->MSR = CAN_MSR_SLAKI;
    TT_CHECK(!(CAN->MSR & CAN_MSR_SLAKI));
    /* The master reset: back to the reset state, asleep. */
    CAN->MCR = CAN_MCR_RESET;
    TT_CHECK(CAN->MCR == 0x00010002u);
    TT_CHECK(CAN->BTR == 0x01230000u);
}

/* ---- TIM11's channel 1 on HSE_RTC: the crystal measured against the HSI ---- */

#define TIM11 ((tse_tim_regs *)0x40014800u)
#define TIM11_OR (*(volatile uint32_t *)0x40014850u)
#define APB2ENR_TIM11 (1u << 18)
#define CFGR_RTCPRE(n) ((uint32_t)(n) << 16)
#define SR_CC1OF (1u << 9)

/* Two captures in a row: the counts between them. */
static uint32_t capture_interval(void)
{
    TIM11->SR = 0;
    (void)TIM11->CCR1;
    if (wait_for(&TIM11->SR, TIM_SR_CC1IF, TIM_SR_CC1IF, 1000) == UINT32_MAX)
        return UINT32_MAX;
    const uint32_t a = TIM11->CCR1;
    if (TIM11->SR & TIM_SR_CC1IF) /* the read clears it */
        return UINT32_MAX - 1;
    if (wait_for(&TIM11->SR, TIM_SR_CC1IF, TIM_SR_CC1IF, 1000) == UINT32_MAX)
        return UINT32_MAX;
    return (TIM11->CCR1 - a) & 0xFFFFu;
}

static void tim11_hse_rtc_capture(void)
{
    TSE_RCC->CR |= RCC_CR_HSEON;
    TT_CHECK(wait_for(&TSE_RCC->CR, RCC_CR_HSERDY, RCC_CR_HSERDY, 20000) != UINT32_MAX);
    TSE_RCC->APB2ENR |= APB2ENR_TIM11;
    TIM11->PSC = 0;
    TIM11->ARR = 0xFFFF;
    TIM11->EGR = TIM_EGR_UG;
    TIM11->CCMR1 = 0x1u | 0x3u << 2; /* CC1S = 01: IC1 on TI1; IC1PSC = 11: every 8 events */
    TIM11->CCER = 1u;                /* CC1E, rising edges */
    TIM11->CR1 = TIM_CR1_CEN;
    /* TI1 still on its pin (OR 0): nothing to capture. */
    TT_CHECK(capture_interval() == UINT32_MAX);
    /* On HSE_RTC with RTCPRE 0: no clock (RM0090 7.3.3: 0 and 1 give none). */
    TIM11_OR = 2u;
    TT_CHECK(capture_interval() == UINT32_MAX);
    /* HSE / 31 every 8 edges: 248 periods of 8 MHz, 496 ticks of 16 MHz (a tick either way:
     * the edges do not fall on the counter's). */
    TSE_RCC->CFGR |= CFGR_RTCPRE(31);
    uint32_t n = capture_interval();
    TT_CHECKF(n >= 495 && n <= 497, "8 x HSE/31: %lu ticks\n", (unsigned long)n);
    /* Every edge of HSE / 8: 16 ticks. */
    TSE_RCC->CFGR = (TSE_RCC->CFGR & ~CFGR_RTCPRE(31)) | CFGR_RTCPRE(8);
    TIM11->CCMR1 = 0x1u;
    n = capture_interval();
    TT_CHECKF(n >= 15 && n <= 17, "HSE/8: %lu ticks\n", (unsigned long)n);
    /* A capture not read before the next: CC1OF as well. */
    TIM11->SR = 0;
    (void)TIM11->CCR1;
    spin_us(10);
    TT_CHECK((TIM11->SR & (TIM_SR_CC1IF | SR_CC1OF)) == (TIM_SR_CC1IF | SR_CC1OF));
    /* In input mode CCR1 is read-only. */
    const uint32_t held = TIM11->CCR1;
    TIM11->CCER = 0;
    TIM11->CCR1 = held ^ 0x5555u;
    TT_CHECK(TIM11->CCR1 == held);
    /* The crystal off: no HSE_RTC. */
    TIM11->CCER = 1u;
    TSE_RCC->CR &= ~RCC_CR_HSEON;
    TT_CHECK(capture_interval() == UINT32_MAX);
    TIM11->CR1 = 0;
    TIM11->CCER = 0;
    TIM11_OR = 0;
    TSE_RCC->CFGR &= ~CFGR_RTCPRE(31);
    TSE_RCC->APB2ENR &= ~APB2ENR_TIM11;
}

/* ---- the PLL, last: it changes the clocks the cases above count with ---- */

static void rcc_pll(void)
{
    TSE_RCC->CR |= RCC_CR_HSEON;
    TT_CHECK(!(TSE_RCC->CR & RCC_CR_HSERDY));
    const uint32_t hse = wait_for(&TSE_RCC->CR, RCC_CR_HSERDY, RCC_CR_HSERDY, 20000);
    TT_CHECKF(hse >= 500 && hse != UINT32_MAX, "HSERDY after %lu us\n", (unsigned long)hse);
    /* M = 2: a 4 MHz VCO input, outside 0.95..2.1 MHz: the PLL never locks. */
    TSE_RCC->PLLCFGR = RCC_PLLCFGR(2, 168, 2, 7) | RCC_PLLCFGR_SRC_HSE;
    TSE_RCC->CR |= RCC_CR_PLLON;
    TT_CHECK(wait_for(&TSE_RCC->CR, RCC_CR_PLLRDY, RCC_CR_PLLRDY, 5000) == UINT32_MAX);
    TSE_RCC->CR &= ~RCC_CR_PLLON;
    const uint32_t good = RCC_PLLCFGR(4, 168, 2, 7) | RCC_PLLCFGR_SRC_HSE;
    TSE_RCC->PLLCFGR = good;
    TSE_RCC->CR |= RCC_CR_PLLON;
    TSE_RCC->PLLCFGR = RCC_PLLCFGR(8, 168, 2, 7) | RCC_PLLCFGR_SRC_HSE; /* while on: ignored */
    TT_CHECK(TSE_RCC->PLLCFGR == good);
    /* SW asks for the PLL before it is ready: SWS follows only once it is. */
    TSE_FLASH->ACR = 5;
    TSE_RCC->CFGR = RCC_CFGR_PPRE1_DIV4 | RCC_CFGR_PPRE2_DIV2 | RCC_CFGR_SW_PLL;
    TT_CHECK((TSE_RCC->CFGR & RCC_CFGR_SWS_MASK) == 0);
    const uint32_t lock = wait_for(&TSE_RCC->CFGR, RCC_CFGR_SWS_MASK, RCC_CFGR_SWS_PLL, 5000);
    TT_CHECKF(lock != UINT32_MAX, "SWS never followed\n");
    /* TIM5 counted at 16 MHz / 16; now at 84 MHz / 16. */
    const uint32_t c0 = now_us();
    for (volatile int i = 0; i < 2000; ++i)
        ;
    TT_CHECK(now_us() != c0);
    TSE_TIM5->PSC = 83;
    TSE_TIM5->EGR = TIM_EGR_UG;
    /* HSE and the PLL cannot be switched off while they feed SYSCLK. */
    TSE_RCC->CR &= ~(RCC_CR_HSEON | RCC_CR_PLLON);
    TT_CHECK((TSE_RCC->CR & (RCC_CR_HSEON | RCC_CR_PLLON)) == (RCC_CR_HSEON | RCC_CR_PLLON));
}

int main(void)
{
    tt_begin("emulator models");
    clock_us_start();
    tt_case("rcc_reset_state", rcc_reset_state);
    tt_case("rcc_clock_gates", rcc_clock_gates);
    tt_case("gpio_pins", gpio_pins);
    tt_case("gpio_lock", gpio_lock);
    tt_case("exti_edges", exti_edges);
    tt_case("tim_update_generation", tim_update_generation);
    tt_case("tim_one_pulse", tim_one_pulse);
    tt_case("tim_prescaler_preload", tim_prescaler_preload);
    tt_case("iwdg_write_access", iwdg_write_access);
    tt_case("flash_program", flash_program);
    tt_case("flash_erase", flash_erase);
    tt_case("flash_wrong_key", flash_wrong_key);
    tt_case("can_modes_and_filters", can_modes_and_filters);
    tt_case("can_request_order", can_request_order);
    tt_case("can_overrun", can_overrun);
    tt_case("can_sleep", can_sleep);
    tt_case("tim11_hse_rtc_capture", tim11_hse_rtc_capture);
    tt_case("rcc_pll", rcc_pll);
    tt_finish();
}
