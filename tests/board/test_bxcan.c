/* The bxCAN driver on a fake register block in RAM, driven by a model of the controller written
 * here from the reference manual (RM0090 32.4, 32.7, 32.8):
 * - INAK follows INRQ, SLAK follows SLEEP (when the model is "responsive"; QEMU's all-zero
 *   registers when not); leaving initialisation needs an idle bus;
 * - TSR, RF0R and MSR's write-1-to-clear and release bits: plain RAM keeps only the last value
 *   written, so after every driver call the model compares each with what it put there and
 *   applies the difference as the write it was;
 * - mailboxes go out in request order (TXFP), one per call of transmit_one(); three-deep FIFO 0
 *   with overrun; the interrupt lines TX = TMEIE & RQCPx, RX0 = FMPIE0 & FMP != 0,
 *   SCE = ERRIE & ERRI, "taken" (the ISR called) while they are high, like the NVIC.
 * The model only learns of a mailbox request when it syncs, so mailboxes loaded in one driver
 * call are taken as requested in mailbox order; the tests load at most one mailbox per call
 * where the order matters. */
#include <setjmp.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#include <cmocka.h>
#include <string.h>

#include "hal_stm32f4/bxcan.h"

/* Bits as RM0090 defines them, spelled out here (not taken from regs_can.h). */
enum {
    MCR_INRQ = 1 << 0, MCR_SLEEP = 1 << 1, MCR_TXFP = 1 << 2, MCR_NART = 1 << 4,
    MCR_AWUM = 1 << 5, MCR_ABOM = 1 << 6,
    MSR_INAK = 1 << 0, MSR_SLAK = 1 << 1, MSR_ERRI = 1 << 2, MSR_SAMP = 1 << 10, MSR_RX = 1 << 11,
    RF_FULL = 1 << 3, RF_FOVR = 1 << 4, RF_RFOM = 1 << 5,
    IER_TMEIE = 1 << 0, IER_FMPIE0 = 1 << 1, IER_EPVIE = 1 << 9, IER_BOFIE = 1 << 10,
    IER_ERRIE = 1 << 15,
    ESR_EWGF = 1 << 0, ESR_EPVF = 1 << 1, ESR_BOFF = 1 << 2,
    FMR_FINIT = 1 << 0,
};
#define TSR_RQCP(m) (1u << (8 * (m)))
#define TSR_TXOK(m) (2u << (8 * (m)))
#define TSR_TME(m) (1u << (26 + (m)))

typedef struct {
    uint32_t rir, rdtr, rdlr, rdhr;
} raw_frame;

static tse_can_regs hw;
static bxcan_dev dev;
static hal_can can;

static struct {
    bool responsive, bus_idle, sleep_stuck, irqs_on;
    bool inak, slak, erri;
    uint32_t msr, tsr, rf0r, esr; /* what the model last put in the registers */
    bool pending[3], rqcp[3];
    uint32_t seq[3], next_seq;
    raw_frame fifo[3];
    unsigned fmp;
    bool full, fovr;
    hal_can_frame sent[64];
    unsigned nsent;
    unsigned idle_calls, isr_calls;
    uint32_t btr_at_first_wait;  /* BTR when the driver first waited (entering init) */
    bool saw_leave_request;
    uint32_t btr_at_leave, fmr_at_leave, ier_at_leave; /* when INRQ was first seen cleared */
} m;

/* ---- the model ---- */

static void sync_msr(void)
{
    const uint32_t written = hw.MSR;
    if (written != m.msr && (written & MSR_ERRI))
        m.erri = false;
    if (m.responsive) {
        const uint32_t mcr = hw.MCR;
        m.slak = m.sleep_stuck || ((mcr & MCR_SLEEP) && !(mcr & MCR_INRQ));
        if (mcr & MCR_INRQ)
            m.inak = true;
        else if (m.bus_idle)
            m.inak = false;
    }
    m.msr = (m.inak ? MSR_INAK : 0u) | (m.slak ? MSR_SLAK : 0u) | (m.erri ? MSR_ERRI : 0u);
    if (m.responsive) /* the CANRX level, recessive: also tells a written MSR from ours */
        m.msr |= MSR_SAMP | MSR_RX;
    hw.MSR = m.msr;
}

static void sync_tsr(void)
{
    const uint32_t written = hw.TSR;
    for (int b = 0; b < 3; ++b) {
        if (written != m.tsr && (written & TSR_RQCP(b)))
            m.rqcp[b] = false;
        if (!m.pending[b] && (hw.TX[b].TIR & 1u)) { /* TXRQ: a new request */
            m.pending[b] = true;
            m.seq[b] = m.next_seq++;
        }
    }
    uint32_t tsr = 0;
    for (int b = 0; b < 3; ++b)
        tsr |= (m.pending[b] ? 0u : TSR_TME(b)) | (m.rqcp[b] ? TSR_RQCP(b) | TSR_TXOK(b) : 0u);
    m.tsr = tsr;
    hw.TSR = tsr;
}

static void sync_rf0r(void)
{
    const uint32_t written = hw.RF0R;
    if (written != m.rf0r) {
        if ((written & RF_RFOM) && m.fmp > 0) {
            memmove(&m.fifo[0], &m.fifo[1], 2 * sizeof m.fifo[0]);
            --m.fmp;
        }
        if (written & RF_FOVR)
            m.fovr = false;
        if (written & RF_FULL)
            m.full = false;
    }
    const raw_frame out = m.fmp ? m.fifo[0] : (raw_frame){0, 0, 0, 0};
    hw.RX[0].RIR = out.rir;
    hw.RX[0].RDTR = out.rdtr;
    hw.RX[0].RDLR = out.rdlr;
    hw.RX[0].RDHR = out.rdhr;
    m.rf0r = m.fmp | (m.full ? RF_FULL : 0u) | (m.fovr ? RF_FOVR : 0u);
    hw.RF0R = m.rf0r;
}

static void sync_regs(void)
{
    sync_msr();
    sync_tsr();
    sync_rf0r();
}

/* Takes interrupts while a line is high, like the NVIC (bounded: a stuck line fails). */
static void dispatch(void)
{
    for (int n = 0; m.irqs_on; ++n) {
        assert_true(n < 100);
        const uint32_t ier = hw.IER;
        if ((ier & IER_TMEIE) && (m.rqcp[0] || m.rqcp[1] || m.rqcp[2]))
            bxcan_tx_isr(&dev);
        else if ((ier & IER_FMPIE0) && m.fmp > 0)
            bxcan_rx0_isr(&dev);
        else if ((ier & IER_ERRIE) && m.erri)
            bxcan_sce_isr(&dev);
        else
            return;
        ++m.isr_calls;
        sync_regs();
    }
}

static void run(void)
{
    sync_regs();
    dispatch();
}

/* The driver's idle hook during init: the controller reacts between polls. */
static void model_idle(void)
{
    if (m.idle_calls++ == 0)
        m.btr_at_first_wait = hw.BTR;
    if (!m.saw_leave_request && m.inak && !(hw.MCR & MCR_INRQ)) {
        m.saw_leave_request = true;
        m.btr_at_leave = hw.BTR;
        m.fmr_at_leave = hw.FMR;
        m.ier_at_leave = hw.IER;
    }
    sync_regs();
}

/* The bus takes the oldest request (TXFP: request order) and acknowledges it. */
static bool transmit_one(void)
{
    int b = -1;
    for (int i = 0; i < 3; ++i)
        if (m.pending[i] && (b < 0 || m.seq[i] < m.seq[b]))
            b = i;
    if (b < 0)
        return false;
    const uint32_t tir = hw.TX[b].TIR, len = hw.TX[b].TDTR & 0xFu;
    assert_int_equal(tir & 0x6u, 0); /* a standard data frame: IDE = RTR = 0 */
    assert_true(len <= 8);
    hal_can_frame *f = &m.sent[m.nsent++];
    f->id = (uint16_t)(tir >> 21);
    f->len = (uint8_t)len;
    const uint32_t lo = hw.TX[b].TDLR, hi = hw.TX[b].TDHR;
    for (int i = 0; i < 4; ++i) {
        f->data[i] = (uint8_t)(lo >> (8 * i));
        f->data[4 + i] = (uint8_t)(hi >> (8 * i));
    }
    hw.TX[b].TIR = tir & ~1u; /* hardware clears TXRQ */
    m.pending[b] = false;
    m.rqcp[b] = true;
    run();
    return true;
}

static raw_frame std_frame(uint16_t id, uint32_t dlc, uint32_t lo, uint32_t hi)
{
    const raw_frame f = {(uint32_t)id << 21, dlc, lo, hi};
    return f;
}

/* A frame that passed the filter arrives in FIFO 0 (RFLM = 0: when full, the newest overwrites
 * the last and FOVR is set). */
static void receive_raw(raw_frame f)
{
    if (m.fmp == 3) {
        m.fifo[2] = f;
        m.fovr = true;
    } else {
        m.fifo[m.fmp++] = f;
    }
    m.full = m.fmp == 3;
    run();
}

/* The error counters move: ERRI is raised when EPVF or BOFF gets set and its interrupt is on. */
static void set_esr(uint32_t esr)
{
    const uint32_t rising = esr & ~m.esr, ier = hw.IER;
    if (((rising & ESR_EPVF) && (ier & IER_EPVIE)) || ((rising & ESR_BOFF) && (ier & IER_BOFIE)))
        m.erri = true;
    m.esr = esr;
    hw.ESR = esr;
    run();
}

static void reset_model(bool responsive)
{
    memset((void *)&hw, 0, sizeof hw);
    memset(&m, 0, sizeof m);
    m.responsive = responsive;
    m.bus_idle = true;
    if (responsive) { /* the reset values: asleep, filters in init, CAN2SB = 14 */
        hw.MCR = 0x00010002u;
        hw.MSR = MSR_SLAK | MSR_SAMP | MSR_RX; /* 0x00000C02 */
        hw.FMR = 0x2A1C0E01u;
        m.slak = true;
    }
    m.msr = hw.MSR;
    sync_tsr();
    m.rf0r = hw.RF0R;
}

/* A working controller, initialised for node 5 at 500 kbit/s from 42 MHz, interrupts on. */
static int setup_running(void **state)
{
    (void)state;
    reset_model(true);
    assert_int_equal(bxcan_init(&dev, &hw, 42000000u, 500000u, 5, model_idle), BXCAN_OK);
    can = bxcan_hal(&dev);
    m.irqs_on = true;
    run();
    return 0;
}

static hal_can_frame frame(uint32_t n)
{
    hal_can_frame f;
    f.id = (uint16_t)(0x100u + n);
    f.len = (uint8_t)(n % 9u);
    for (int i = 0; i < 8; ++i)
        f.data[i] = (uint8_t)(i < f.len ? n * 16u + (uint32_t)i : 0u);
    return f;
}

static int send(uint32_t n)
{
    const hal_can_frame f = frame(n);
    const int r = can.send(can.ctx, &f);
    run();
    return r;
}

static void assert_frame(const hal_can_frame *f, uint32_t n)
{
    const hal_can_frame e = frame(n);
    assert_int_equal(f->id, e.id);
    assert_int_equal(f->len, e.len);
    assert_memory_equal(f->data, e.data, e.len);
}

static unsigned pending_count(void)
{
    return (unsigned)m.pending[0] + m.pending[1] + m.pending[2];
}

/* ---- initialisation ---- */

static void init_sequence(void **state)
{
    (void)state;
    reset_model(true);
    hw.FA1R = 1u << 20; /* a CAN2 bank in use: must survive */
    hw.FB[20].FR1 = 0xDEADBEEFu;
    assert_int_equal(bxcan_init(&dev, &hw, 42000000u, 500000u, 5, model_idle), BXCAN_OK);
    const uint32_t mcr = hw.MCR;
    assert_true(mcr & MCR_ABOM);
    assert_true(mcr & MCR_AWUM);
    assert_true(mcr & MCR_TXFP);
    assert_false(mcr & (MCR_INRQ | MCR_SLEEP | MCR_NART)); /* running, retransmitting */
    assert_int_equal(hw.MSR & (MSR_INAK | MSR_SLAK), 0);
    /* BTR written in initialisation mode, not before; by RM0090's formula 500 kbit/s exactly. */
    assert_int_equal(m.btr_at_first_wait, 0);
    assert_true(m.saw_leave_request);
    const uint32_t btr = hw.BTR, brp = (btr & 0x3FFu) + 1u;
    const uint32_t quanta = 1u + ((btr >> 16) & 0xFu) + 1u + ((btr >> 20) & 0x7u) + 1u;
    assert_int_equal(brp * quanta * 500000u, 42000000u);
    assert_int_equal(m.btr_at_leave, btr);
    /* Filters installed before leaving init: bank 0 active, mask mode, 16-bit, FIFO 0, with the
     * hand-derived values for node 5 (bxcan_filter's test covers every identifier). */
    assert_int_equal(m.fmr_at_leave & FMR_FINIT, 0);
    assert_int_equal(hw.FA1R, 1u << 0 | 1u << 20);
    assert_int_equal(hw.FM1R & 1u, 0);
    assert_int_equal(hw.FS1R & 1u, 0);
    assert_int_equal(hw.FFA1R & 1u, 0);
    assert_int_equal(hw.FB[0].FR1, 0x01F800A0u);
    assert_int_equal(hw.FB[0].FR2, 0x01F80000u);
    assert_int_equal(hw.FB[20].FR1, 0xDEADBEEFu);
    assert_int_equal(hw.FMR & 0x3F00u, 14u << 8); /* CAN2SB kept */
    /* Interrupts: FIFO 0 pending, TX mailbox empty, error-passive and bus-off via ERRI. */
    const uint32_t want = IER_FMPIE0 | IER_TMEIE | IER_BOFIE | IER_EPVIE | IER_ERRIE;
    assert_int_equal(m.ier_at_leave & want, want);
    assert_int_equal(hw.IER & want, want);
}

/* QEMU: every register reads zero.  The first wait gives up after BXCAN_WAIT_LOOPS polls. */
static void init_no_controller(void **state)
{
    (void)state;
    reset_model(false);
    assert_int_equal(bxcan_init(&dev, &hw, 42000000u, 500000u, 5, model_idle),
                     BXCAN_ERR_ENTER_INIT);
    assert_int_equal(m.idle_calls, BXCAN_WAIT_LOOPS);
    /* The hal still works: frames queue and go nowhere, nothing is received. */
    can = bxcan_hal(&dev);
    hal_can_frame f = frame(1);
    assert_int_equal(can.send(can.ctx, &f), 0);
    assert_int_equal(can.receive(can.ctx, &f), 0);
    hal_can_state st;
    can.state(can.ctx, &st);
    assert_false(st.bus_off);
}

static void init_stays_asleep(void **state)
{
    (void)state;
    reset_model(true);
    m.sleep_stuck = true;
    assert_int_equal(bxcan_init(&dev, &hw, 42000000u, 500000u, 5, model_idle), BXCAN_ERR_WAKE);
}

/* No transceiver: the controller never sees 11 recessive bits, so never leaves init. */
static void init_no_bus(void **state)
{
    (void)state;
    reset_model(true);
    m.bus_idle = false;
    assert_int_equal(bxcan_init(&dev, &hw, 42000000u, 500000u, 5, model_idle),
                     BXCAN_ERR_LEAVE_INIT);
    assert_int_not_equal(hw.BTR, 0); /* configured all the same */
    assert_int_equal(hw.MCR & MCR_INRQ, 0);
}

static void init_bad_arguments(void **state)
{
    (void)state;
    reset_model(true);
    assert_int_equal(bxcan_init(&dev, &hw, 42000000u, 800000u, 5, model_idle), BXCAN_ERR_TIMING);
    assert_int_equal(bxcan_init(&dev, &hw, 42000000u, 500000u, 0, model_idle), BXCAN_ERR_NODE);
    assert_int_equal(bxcan_init(&dev, &hw, 42000000u, 500000u, 16, model_idle), BXCAN_ERR_NODE);
    assert_int_equal(hw.MCR, 0x00010002u); /* nothing touched */
    assert_int_equal(m.idle_calls, 0);
    assert_string_equal(bxcan_status_str(BXCAN_ERR_LEAVE_INIT),
                        "INAK never cleared (bus never idle)");
}

/* ---- transmission ---- */

/* Twelve frames: three fill the mailboxes (loaded one per send, so the model knows their
 * order), nine wait in the ring; as the bus completes each, the TX interrupt loads the next.
 * They leave in the order sent, intact. */
static void burst_leaves_in_order(void **state)
{
    (void)state;
    for (uint32_t n = 0; n < 12; ++n) {
        assert_int_equal(send(n), 0);
        assert_int_equal(pending_count(), n < 3 ? n + 1 : 3);
    }
    assert_int_equal(can_ring_count(&dev.tx), 9);
    const unsigned isr_before = m.isr_calls;
    while (transmit_one())
        ;
    assert_int_equal(m.nsent, 12);
    for (uint32_t n = 0; n < 12; ++n)
        assert_frame(&m.sent[n], n);
    assert_int_equal(m.isr_calls - isr_before, 12); /* one TX interrupt per completion */
    assert_int_equal(can_ring_count(&dev.tx), 0);
    assert_false(m.rqcp[0] || m.rqcp[1] || m.rqcp[2]); /* every completion acknowledged */
}

/* Sends interleaved with completions: mailboxes free up in a rotating order. */
static void interleaved_sends(void **state)
{
    (void)state;
    uint32_t next = 0;
    for (int round = 0; round < 40; ++round) {
        for (int k = 0; k < round % 4; ++k)
            assert_int_equal(send(next++), 0);
        for (int k = 0; k < round % 3; ++k)
            transmit_one();
    }
    while (transmit_one())
        ;
    assert_int_equal(m.nsent, next);
    for (uint32_t n = 0; n < next; ++n)
        assert_frame(&m.sent[n], n);
}

/* No bus: three mailboxes and 32 ring slots hold 35 frames; the 36th is refused. */
static void full_ring_refuses(void **state)
{
    (void)state;
    for (uint32_t n = 0; n < 3 + CAN_RING_CAPACITY; ++n)
        assert_int_equal(send(n), 0);
    assert_int_equal(send(99), -1);
    assert_int_equal(can_ring_dropped(&dev.tx), 1);
    while (transmit_one())
        ;
    assert_int_equal(m.nsent, 3 + CAN_RING_CAPACITY);
    for (uint32_t n = 0; n < m.nsent; ++n)
        assert_frame(&m.sent[n], n);
}

/* The TX interrupt leaves the mailboxes alone while TMEIE is clear (send's kick owns them then),
 * and the kick restores TMEIE. */
static void tx_isr_yields_to_kick(void **state)
{
    (void)state;
    for (uint32_t n = 0; n < 4; ++n)
        assert_int_equal(send(n), 0);
    assert_int_equal(hw.IER & IER_TMEIE, IER_TMEIE);
    m.irqs_on = false; /* a completion whose interrupt is still to be taken */
    transmit_one();
    hw.IER &= ~(uint32_t)IER_TMEIE;
    bxcan_tx_isr(&dev);
    sync_regs();
    assert_int_equal(pending_count(), 2);
    hw.IER |= IER_TMEIE;
    bxcan_tx_isr(&dev);
    sync_regs();
    assert_int_equal(pending_count(), 3);
    m.irqs_on = true;
    while (transmit_one())
        ;
    for (uint32_t n = 0; n < 4; ++n)
        assert_frame(&m.sent[n], n);
}

/* Out-of-range fields are cut, never spilled into other bits. */
static void oversized_fields(void **state)
{
    (void)state;
    hal_can_frame f = frame(3);
    f.id = 0xF123u;
    f.len = 12;
    memset(f.data, 0xAB, 8);
    assert_int_equal(can.send(can.ctx, &f), 0);
    run();
    assert_true(transmit_one());
    assert_int_equal(m.sent[0].id, 0x123);
    assert_int_equal(m.sent[0].len, 8);
}

/* ---- reception ---- */

static void rx_drains_into_ring(void **state)
{
    (void)state;
    for (uint32_t n = 0; n < 6; ++n)
        receive_raw(std_frame((uint16_t)(0x105u + 16u * n), n, 0x03020100u + n, 0x07060504u));
    assert_int_equal(m.fmp, 0); /* drained as they came */
    hal_can_frame f;
    for (uint32_t n = 0; n < 6; ++n) {
        assert_int_equal(can.receive(can.ctx, &f), 1);
        assert_int_equal(f.id, 0x105u + 16u * n);
        assert_int_equal(f.len, n);
        const uint8_t want[8] = {(uint8_t)n, 1, 2, 3, 4, 5, 6, 7};
        assert_memory_equal(f.data, want, n);
    }
    assert_int_equal(can.receive(can.ctx, &f), 0);
    /* DLC 9..15 means 8 bytes. */
    receive_raw(std_frame(0x205, 15, 0x44332211u, 0x88776655u));
    assert_int_equal(can.receive(can.ctx, &f), 1);
    assert_int_equal(f.len, 8);
    assert_int_equal(f.data[7], 0x88);
    /* An extended or remote frame (the filter admits none) never reaches the firmware. */
    receive_raw((raw_frame){0x105u << 21 | 1u << 2, 0, 0, 0});
    receive_raw((raw_frame){0x105u << 21 | 1u << 1, 0, 0, 0});
    assert_int_equal(m.fmp, 0);
    assert_int_equal(can.receive(can.ctx, &f), 0);
}

/* Four frames while the interrupt is held off: FIFO 0 keeps three and overruns once. */
static void fifo_overrun_counted(void **state)
{
    (void)state;
    m.irqs_on = false;
    for (uint32_t n = 0; n < 4; ++n)
        receive_raw(std_frame((uint16_t)(0x115u + 16u * n), 1, n, 0));
    assert_true(m.fovr);
    m.irqs_on = true;
    run();
    assert_int_equal(m.fmp, 0);
    assert_false(m.fovr); /* acknowledged */
    assert_false(m.full);
    hal_can_frame f;
    uint32_t got = 0;
    while (can.receive(can.ctx, &f) == 1)
        ++got;
    assert_int_equal(got, 3);
    hal_can_state st;
    can.state(can.ctx, &st);
    assert_int_equal(st.rx_overruns, 1);
}

/* The firmware does not read for a while: the ring keeps 32, the rest count as overruns. */
static void ring_overflow_counted(void **state)
{
    (void)state;
    for (uint32_t n = 0; n < CAN_RING_CAPACITY + 8u; ++n)
        receive_raw(std_frame((uint16_t)(0x105u + 16u * (n % 64u)), 2, n, 0));
    hal_can_state st;
    can.state(can.ctx, &st);
    assert_int_equal(st.rx_overruns, 8);
    hal_can_frame f;
    for (uint32_t n = 0; n < CAN_RING_CAPACITY; ++n) {
        assert_int_equal(can.receive(can.ctx, &f), 1);
        assert_int_equal(f.data[0], (uint8_t)n); /* the first 32, in order */
    }
    assert_int_equal(can.receive(can.ctx, &f), 0);
}

/* ---- error state ---- */

static void error_counters_reported(void **state)
{
    (void)state;
    hal_can_state st;
    set_esr(0x7Fu << 24 | 0x60u << 16 | ESR_EWGF);
    can.state(can.ctx, &st);
    assert_int_equal(st.tx_errors, 0x60);
    assert_int_equal(st.rx_errors, 0x7F);
    assert_false(st.error_passive);
    assert_false(st.bus_off);
    set_esr(0x10u << 24 | 0x88u << 16 | ESR_EWGF | ESR_EPVF);
    can.state(can.ctx, &st);
    assert_int_equal(st.tx_errors, 0x88);
    assert_int_equal(st.rx_errors, 0x10);
    assert_true(st.error_passive);
    assert_false(st.bus_off);
    assert_int_equal(st.rx_overruns, 0);
}

/* Error-passive, then bus-off (TEC past 255), then recovery by ABOM (counters back to 0). */
static void bus_off_cycle(void)
{
    set_esr(0x80u << 16 | ESR_EWGF | ESR_EPVF);
    set_esr(0xF8u << 16 | ESR_EWGF | ESR_EPVF | ESR_BOFF);
    set_esr(0);
}

static void bus_off_counted(void **state)
{
    (void)state;
    hal_can_state st;
    bus_off_cycle(); /* already recovered when the firmware looks */
    assert_int_equal(atomic_load(&dev.bus_off_events), 1);
    can.state(can.ctx, &st);
    assert_false(st.bus_off);
    assert_int_equal(st.bus_off_events, 1);
    can.state(can.ctx, &st);
    assert_int_equal(st.bus_off_events, 1); /* a second reader sees it too */
    bus_off_cycle();
    bus_off_cycle(); /* two between looks: both counted */
    can.state(can.ctx, &st);
    assert_false(st.bus_off);
    assert_int_equal(st.bus_off_events, 3);
    /* Still in bus-off: reported on every look, counted once even if ERRI fires again. */
    set_esr(0x80u << 16 | ESR_EPVF);
    set_esr(0xF8u << 16 | ESR_EPVF | ESR_BOFF);
    m.erri = true; /* a second error interrupt during the same bus-off */
    run();
    can.state(can.ctx, &st);
    assert_true(st.bus_off);
    assert_true(st.error_passive);
    can.state(can.ctx, &st);
    assert_true(st.bus_off);
    assert_int_equal(st.bus_off_events, 4);
    set_esr(0);
    can.state(can.ctx, &st);
    assert_false(st.bus_off);
    assert_false(m.erri); /* every error interrupt acknowledged */
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(init_sequence),
        cmocka_unit_test(init_no_controller),
        cmocka_unit_test(init_stays_asleep),
        cmocka_unit_test(init_no_bus),
        cmocka_unit_test(init_bad_arguments),
        cmocka_unit_test_setup(burst_leaves_in_order, setup_running),
        cmocka_unit_test_setup(interleaved_sends, setup_running),
        cmocka_unit_test_setup(full_ring_refuses, setup_running),
        cmocka_unit_test_setup(tx_isr_yields_to_kick, setup_running),
        cmocka_unit_test_setup(oversized_fields, setup_running),
        cmocka_unit_test_setup(rx_drains_into_ring, setup_running),
        cmocka_unit_test_setup(fifo_overrun_counted, setup_running),
        cmocka_unit_test_setup(ring_overflow_counted, setup_running),
        cmocka_unit_test_setup(error_counters_reported, setup_running),
        cmocka_unit_test_setup(bus_off_counted, setup_running),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
