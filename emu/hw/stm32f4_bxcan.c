/*
 * STM32F405/407 bxCAN controller CAN1 (RM0090 section 32) on a QEMU CAN bus (-object can-bus,
 * the machine's "canbus" link), with the filter banks CAN1 and CAN2 share.
 *
 * Modelled:
 * - Modes: sleep (the reset state), initialisation and normal, with their handshakes: INAK/SLAK
 *   follow INRQ/SLEEP once the frame on the bus (if any) has ended; leaving initialisation or
 *   sleep takes 11 recessive bits at the configured bit rate before the controller is on the bus,
 *   and never completes while the bus is held in error ("bus-error" line: the rig's canerr).  A
 *   frame on the bus wakes a sleeping controller when AWUM is set (WKUI; that frame is lost).
 *   MCR.RESET resets the controller (not the filters) to sleep.
 * - Bit timing: BTR is writable in initialisation only; the controller's bit rate is
 *   PCLK1 / ((BRP+1) x (3+TS1+TS2)), with PCLK1 from the RCC model.  It takes part in the bus
 *   only when that rate matches the bus's ("bus-bitrate", the --bitrate of run.sh) within the
 *   oscillator tolerance its own timing allows (ISO 11898's two conditions: min(PS1,PS2) /
 *   (2 (13 NBT - PS2)) and SJW / (20 NBT), doubled for two nodes): otherwise it receives
 *   nothing (each frame on the bus counts as a receive error) and its transmissions meet the
 *   other nodes' error flags (bit error, TEC + 8 each try: bus-off).
 * - Three transmit mailboxes, sent by identifier priority or, with TXFP, in request order; each
 *   frame takes its nominal length on the bus (44 + 8 x len bits standard, 64 + 8 x len
 *   extended, plus 3 bits of intermission; no stuff bits); RQCP/TXOK/TERR/TME, CODE and LOW in
 *   TSR; abort (ABRQ); automatic retransmission unless NART.  A transmission succeeds when a
 *   node on the bus acknowledges it (the bus layer's answer: our chardev bridge acknowledges
 *   while something is connected to it); otherwise it is an acknowledgement error.
 * - Two receive FIFOs of three frames each, with FMP, FULL, overrun (FOVR; the newest frame is
 *   overwritten, or the incoming one dropped with RFLM) and RFOM; the 28 filter banks in mask
 *   and list modes, 16 and 32 bits, FIFO assignment and match index (stm32f4_bxcan_filter.c);
 *   no reception while FINIT is set.
 * - Errors (ISO 11898-1 fault confinement): TEC + 8 for a transmit error (not for an
 *   acknowledgement error while error passive), - 1 for a success; REC + 1 for a receive error,
 *   - 1 for a success (to 120 from above 127); EWGF (96), EPVF (128), BOFF (TEC > 255); LEC;
 *   bus-off stops the controller until 128 x 11 recessive bits have passed (by itself with
 *   ABOM, else after the software has left initialisation), then TEC = REC = 0.
 * - The four interrupts (TX, RX0, RX1, SCE) as levels of their status bits and IER (ERRI set
 *   on a rise of EWGF/EPVF/BOFF or a new LEC that IER selects).
 * - Loop-back (LBKM) and silent (SILM) modes.
 * - The pins: the controller talks on the bus only while PB8 and PB9 are on alternate function
 *   9 ("rx-af"/"tx-af" from the GPIO model): with CAN RX elsewhere it sees nothing; with CAN TX
 *   elsewhere its frames never reach the bus (bit errors, bus-off).
 * Not modelled: time-triggered mode and time stamps, stuff bits and exact frame timing,
 * arbitration against other nodes' frames (the bus layer has no notion of simultaneity), CAN2
 * (its registers are unimplemented; its filter banks are CAN1's), the debug freeze.
 *
 * SPDX-License-Identifier: GPL-2.0-or-later
 */
#include "qemu/osdep.h"
#include <math.h>
#include "qemu/log.h"
#include "qemu/host-utils.h"
#include "qemu/timer.h"
#include "qapi/error.h"
#include "hw/sysbus.h"
#include "hw/irq.h"
#include "hw/qdev-clock.h"
#include "hw/qdev-properties.h"
#include "net/can_emu.h"
#include "tse_f407.h"
#include "stm32f4_bxcan_filter.h"

OBJECT_DECLARE_SIMPLE_TYPE(Stm32f4BxcanState, STM32F4_BXCAN)

#define R_MCR 0x000
#define R_MSR 0x004
#define R_TSR 0x008
#define R_RF0R 0x00C
#define R_RF1R 0x010
#define R_IER 0x014
#define R_ESR 0x018
#define R_BTR 0x01C
#define R_TX 0x180
#define R_RX 0x1B0
#define R_FMR 0x200
#define R_FM1R 0x204
#define R_FS1R 0x20C
#define R_FFA1R 0x214
#define R_FA1R 0x21C
#define R_FB 0x240

#define MCR_INRQ (1u << 0)
#define MCR_SLEEP (1u << 1)
#define MCR_TXFP (1u << 2)
#define MCR_RFLM (1u << 3)
#define MCR_NART (1u << 4)
#define MCR_AWUM (1u << 5)
#define MCR_ABOM (1u << 6)
#define MCR_TTCM (1u << 7)
#define MCR_RESET (1u << 15)
#define MCR_DBF (1u << 16)
#define MSR_INAK (1u << 0)
#define MSR_SLAK (1u << 1)
#define MSR_ERRI (1u << 2)
#define MSR_WKUI (1u << 3)
#define MSR_SLAKI (1u << 4)
#define MSR_TXM (1u << 8)
#define MSR_RXM (1u << 9)
#define MSR_SAMP (1u << 10)
#define MSR_RX (1u << 11)
#define TSR_RQCP(m) (1u << (8 * (m)))
#define TSR_TXOK(m) (2u << (8 * (m)))
#define TSR_ALST(m) (4u << (8 * (m)))
#define TSR_TERR(m) (8u << (8 * (m)))
#define TSR_ABRQ(m) (0x80u << (8 * (m)))
#define TSR_TME(m) (1u << (26 + (m)))
#define TSR_LOW(m) (1u << (29 + (m)))
#define RFR_FULL (1u << 3)
#define RFR_FOVR (1u << 4)
#define RFR_RFOM (1u << 5)
#define IER_TMEIE (1u << 0)
#define IER_FMPIE(f) (1u << (1 + 3 * (f)))
#define IER_FFIE(f) (1u << (2 + 3 * (f)))
#define IER_FOVIE(f) (1u << (3 + 3 * (f)))
#define IER_EWGIE (1u << 8)
#define IER_EPVIE (1u << 9)
#define IER_BOFIE (1u << 10)
#define IER_LECIE (1u << 11)
#define IER_ERRIE (1u << 15)
#define IER_WKUIE (1u << 16)
#define IER_SLKIE (1u << 17)
#define ESR_EWGF (1u << 0)
#define ESR_EPVF (1u << 1)
#define ESR_BOFF (1u << 2)
#define TIR_TXRQ (1u << 0)
#define IR_RTR (1u << 1)
#define IR_IDE (1u << 2)
#define BTR_LBKM (1u << 30)
#define BTR_SILM (1u << 31)
#define FMR_FINIT (1u << 0)

enum { LEC_NONE, LEC_STUFF, LEC_FORM, LEC_ACK, LEC_BIT_RECESSIVE, LEC_BIT_DOMINANT, LEC_CRC };
enum { MODE_SLEEP, MODE_INIT, MODE_NORMAL };
enum { IRQ_TX, IRQ_RX0, IRQ_RX1, IRQ_SCE };
#define FIFO_DEPTH 3
#define PIN_AF 9

typedef struct {
    uint32_t ir, dtr, dlr, dhr;
} Mailbox;

struct Stm32f4BxcanState {
    SysBusDevice parent_obj;
    MemoryRegion iomem;
    qemu_irq irq[4];
    qemu_irq rx_out; /* BXCAN_OUT_RX: each frame taken, for an observer */
    Clock *pclk;
    CanBusClientState bus_client;
    CanBusState *canbus;

    uint32_t mcr, msr, tsr, ier, esr, btr;
    uint32_t rfr[2];
    Mailbox tx[3];
    uint32_t tx_order[3];    /* request order, for TXFP */
    uint32_t tx_seq;
    Mailbox fifo[2][FIFO_DEPTH];
    unsigned fmp[2];
    BxcanFilters filters;
    unsigned tec, rec;

    int mode;                /* the mode INAK/SLAK report */
    bool joining;            /* leaving init/sleep: counting 11 recessive bits */
    int tx_box;              /* the mailbox on the bus, or -1 */
    bool recovering;         /* bus-off: counting 128 x 11 recessive bits */
    int64_t busy_until;      /* the end of our frame on the bus */
    QEMUTimer *mode_timer, *tx_timer, *boff_timer;
    bool bus_error;          /* the bus is held in error (the rig's canerr) */
    bool rx_pin, tx_pin;     /* PB8/PB9 on AF9 */

    /* properties */
    uint32_t bus_bitrate;
};

/* ---- bit timing ---- */

/* The controller's bit time in ns (0: no clock). */
static uint64_t bit_ns(Stm32f4BxcanState *s)
{
    const uint64_t hz = clock_get_hz(s->pclk);
    const uint32_t brp = (s->btr & 0x3FF) + 1, ts1 = ((s->btr >> 16) & 0xF) + 1;
    const uint32_t ts2 = ((s->btr >> 20) & 7) + 1;
    if (hz == 0) {
        return 0;
    }
    return muldiv64((uint64_t)brp * (1 + ts1 + ts2), NANOSECONDS_PER_SECOND, hz);
}

/* Whether the controller's bit rate is the bus's, within what its timing tolerates. */
static bool rate_matches(Stm32f4BxcanState *s)
{
    const uint64_t hz = clock_get_hz(s->pclk);
    const uint32_t brp = (s->btr & 0x3FF) + 1, ts1 = ((s->btr >> 16) & 0xF) + 1;
    const uint32_t ts2 = ((s->btr >> 20) & 7) + 1, sjw = ((s->btr >> 24) & 3) + 1;
    const uint32_t nbt = 1 + ts1 + ts2;
    if (hz == 0 || s->bus_bitrate == 0) {
        return false;
    }
    const double rate = (double)hz / ((double)brp * nbt);
    const double ps = ts1 < ts2 ? ts1 : ts2;
    double df = ps / (2.0 * (13.0 * nbt - ts2));
    if ((double)sjw / (20.0 * nbt) < df) {
        df = (double)sjw / (20.0 * nbt);
    }
    return fabs(rate / s->bus_bitrate - 1.0) <= 2.0 * df;
}

static int64_t now_ns(void)
{
    return qemu_clock_get_ns(QEMU_CLOCK_VIRTUAL);
}

static bool on_bus(Stm32f4BxcanState *s)
{
    return s->mode == MODE_NORMAL && !s->joining && !(s->esr & ESR_BOFF);
}

/* ---- interrupts and error state ---- */

static void update_irqs(Stm32f4BxcanState *s)
{
    const uint32_t rqcp = TSR_RQCP(0) | TSR_RQCP(1) | TSR_RQCP(2);
    qemu_set_irq(s->irq[IRQ_TX], (s->ier & IER_TMEIE) && (s->tsr & rqcp));
    for (int f = 0; f < 2; ++f) {
        const bool on = ((s->ier & IER_FMPIE(f)) && s->fmp[f]) ||
                        ((s->ier & IER_FFIE(f)) && (s->rfr[f] & RFR_FULL)) ||
                        ((s->ier & IER_FOVIE(f)) && (s->rfr[f] & RFR_FOVR));
        qemu_set_irq(s->irq[IRQ_RX0 + f], on);
    }
    const bool sce = ((s->ier & IER_ERRIE) && (s->msr & MSR_ERRI)) ||
                     ((s->ier & IER_WKUIE) && (s->msr & MSR_WKUI)) ||
                     ((s->ier & IER_SLKIE) && (s->msr & MSR_SLAKI));
    qemu_set_irq(s->irq[IRQ_SCE], sce);
}

static void boff_recovered(void *opaque);

/* Sets ESR from the counters and the last error code; raises ERRI on what IER selects. */
static void set_error_state(Stm32f4BxcanState *s, int lec)
{
    const uint32_t old = s->esr;
    uint32_t flags = 0;
    if (s->tec >= 96 || s->rec >= 96) {
        flags |= ESR_EWGF;
    }
    if (s->tec > 127 || s->rec > 127) {
        flags |= ESR_EPVF;
    }
    if (s->tec > 255 || (old & ESR_BOFF)) {
        flags |= ESR_BOFF;
    }
    s->esr = (uint32_t)(s->rec > 255 ? 255 : s->rec) << 24 | (uint32_t)(s->tec > 255 ? 255 : s->tec) << 16 |
             (lec >= 0 ? (uint32_t)lec << 4 : (old & 0x70)) | flags;
    const uint32_t rose = flags & ~old;
    if (((rose & ESR_EWGF) && (s->ier & IER_EWGIE)) || ((rose & ESR_EPVF) && (s->ier & IER_EPVIE)) ||
        ((rose & ESR_BOFF) && (s->ier & IER_BOFIE)) || (lec > 0 && (s->ier & IER_LECIE))) {
        s->msr |= MSR_ERRI;
    }
    if ((rose & ESR_BOFF) && (s->mcr & MCR_ABOM)) {
        s->recovering = true;
        timer_mod(s->boff_timer, now_ns() + 128 * 11 * bit_ns(s));
    }
    update_irqs(s);
}

/* 128 x 11 recessive bits seen: out of bus-off (unless the bus is still held in error). */
static void boff_recovered(void *opaque)
{
    Stm32f4BxcanState *s = opaque;
    if (!s->recovering || !(s->esr & ESR_BOFF)) {
        return;
    }
    if (s->bus_error) {
        timer_mod(s->boff_timer, now_ns() + 128 * 11 * bit_ns(s));
        return;
    }
    s->recovering = false;
    s->tec = s->rec = 0;
    s->esr &= ~(ESR_BOFF | ESR_EPVF | ESR_EWGF);
    set_error_state(s, -1);
    timer_mod(s->tx_timer, now_ns());
}

/* ---- modes ---- */

static void update_msr_mode(Stm32f4BxcanState *s)
{
    const bool was_asleep = s->msr & MSR_SLAK;
    s->msr &= ~(MSR_INAK | MSR_SLAK);
    if (s->mode == MODE_INIT) {
        s->msr |= MSR_INAK;
    } else if (s->mode == MODE_SLEEP) {
        s->msr |= MSR_SLAK;
        if (!was_asleep) {
            s->msr |= MSR_SLAKI;
        }
    }
    update_irqs(s);
}

/* Moves towards the mode MCR asks for; called on MCR writes and when a wait ends. */
static void mode_step(void *opaque)
{
    Stm32f4BxcanState *s = opaque;
    const int64_t now = now_ns();
    const int want = (s->mcr & MCR_INRQ) ? MODE_INIT : (s->mcr & MCR_SLEEP) ? MODE_SLEEP : MODE_NORMAL;

    if (want == s->mode && !s->joining) {
        return;
    }
    if (want != MODE_NORMAL) {
        /* Entering init or sleep waits for our frame on the bus to end. */
        if (s->tx_box >= 0 && s->busy_until > now) {
            timer_mod(s->mode_timer, s->busy_until);
            return;
        }
        s->joining = false;
        s->mode = want;
        update_msr_mode(s);
        return;
    }
    /* Leaving init or sleep: 11 recessive bits, which a bus held in error never shows. */
    if (!s->joining) {
        s->joining = true;
        timer_mod(s->mode_timer, now + 11 * bit_ns(s));
        return;
    }
    if (s->bus_error || bit_ns(s) == 0) {
        timer_mod(s->mode_timer, now + 11 * (bit_ns(s) ? bit_ns(s) : 1000));
        return;
    }
    const bool from_init = s->mode == MODE_INIT;
    s->joining = false;
    s->mode = MODE_NORMAL;
    update_msr_mode(s);
    if (from_init && (s->esr & ESR_BOFF) && !(s->mcr & MCR_ABOM)) {
        /* Without ABOM, recovery starts when the software leaves initialisation. */
        s->recovering = true;
        timer_mod(s->boff_timer, now + 128 * 11 * bit_ns(s));
    }
    timer_mod(s->tx_timer, now);
}

/* ---- transmission ---- */

static uint32_t arbitration_key(const Mailbox *m)
{
    const uint32_t stid = m->ir >> 21, exid = (m->ir >> 3) & 0x3FFFF;
    const bool ide = m->ir & IR_IDE, rtr = m->ir & IR_RTR;
    return ide ? stid << 21 | 1u << 20 | 1u << 19 | exid << 1 | rtr : stid << 21 | (uint32_t)rtr << 20;
}

static bool pending(Stm32f4BxcanState *s, int m)
{
    return !(s->tsr & TSR_TME(m));
}

/* The pending mailbox that goes next: request order with TXFP, else identifier priority. */
static int next_box(Stm32f4BxcanState *s)
{
    int best = -1;
    for (int m = 0; m < 3; ++m) {
        if (!pending(s, m)) {
            continue;
        }
        if (best < 0) {
            best = m;
        } else if (s->mcr & MCR_TXFP) {
            if (s->tx_order[m] < s->tx_order[best]) {
                best = m;
            }
        } else if (arbitration_key(&s->tx[m]) < arbitration_key(&s->tx[best])) {
            best = m;
        }
    }
    return best;
}

/* CODE and LOW (RM0090 32.9.2). */
static void update_tsr_code(Stm32f4BxcanState *s)
{
    int code = -1, npending = 0, lowest = -1;
    for (int m = 0; m < 3; ++m) {
        if (!pending(s, m)) {
            if (code < 0) {
                code = m;
            }
            continue;
        }
        ++npending;
        if (lowest < 0 || ((s->mcr & MCR_TXFP) ? s->tx_order[m] > s->tx_order[lowest]
                                                : arbitration_key(&s->tx[m]) > arbitration_key(&s->tx[lowest]))) {
            lowest = m;
        }
    }
    s->tsr &= ~(3u << 24 | 7u << 29);
    if (code >= 0) {
        s->tsr |= (uint32_t)code << 24;
    } else if (lowest >= 0) {
        s->tsr |= (uint32_t)lowest << 24;
    }
    if (npending > 1) {
        s->tsr |= TSR_LOW(lowest);
    }
}

static void release_box(Stm32f4BxcanState *s, int m, bool ok)
{
    s->tsr |= TSR_RQCP(m) | TSR_TME(m) | (ok ? TSR_TXOK(m) : 0);
    if (ok) {
        s->tsr &= ~TSR_TERR(m);
    }
    s->tsr &= ~TSR_ABRQ(m);
    s->tx[m].ir &= ~TIR_TXRQ;
    update_tsr_code(s);
}

static uint32_t frame_bits(const Mailbox *m)
{
    return tse_can_frame_bits(m->ir & IR_IDE, m->ir & IR_RTR, m->dtr & 0xF);
}

static void to_qemu_frame(const Mailbox *m, qemu_can_frame *f)
{
    memset(f, 0, sizeof *f);
    if (m->ir & IR_IDE) {
        f->can_id = ((m->ir >> 3) & QEMU_CAN_EFF_MASK) | QEMU_CAN_EFF_FLAG;
    } else {
        f->can_id = m->ir >> 21;
    }
    if (m->ir & IR_RTR) {
        f->can_id |= QEMU_CAN_RTR_FLAG;
    }
    f->can_dlc = MIN(m->dtr & 0xF, 8);
    for (int i = 0; i < 4; ++i) {
        f->data[i] = m->dlr >> (8 * i);
        f->data[4 + i] = m->dhr >> (8 * i);
    }
}

static void receive_frame(Stm32f4BxcanState *s, const qemu_can_frame *f);

/* The end of our frame on the bus: its outcome. */
static void tx_done(Stm32f4BxcanState *s)
{
    const int m = s->tx_box;
    qemu_can_frame f;
    int lec = LEC_NONE;
    const bool loop = s->btr & BTR_LBKM, silent = s->btr & BTR_SILM;

    s->tx_box = -1;
    to_qemu_frame(&s->tx[m], &f);
    if (!loop && (s->bus_error || !s->tx_pin || !s->rx_pin)) {
        lec = LEC_BIT_RECESSIVE; /* what it sent is not what it reads back */
    } else if (!loop && !rate_matches(s)) {
        lec = LEC_BIT_RECESSIVE; /* the other nodes' error flags over its recessive bits */
    } else {
        const bool acked = silent ? false : can_bus_client_send(&s->bus_client, &f, 1) > 0;
        if (loop) {
            receive_frame(s, &f);
        } else if (!acked) {
            lec = LEC_ACK;
        }
    }

    if (lec == LEC_NONE) {
        if (s->tec > 0) {
            --s->tec;
        }
        release_box(s, m, true);
    } else {
        /* ISO 11898-1 fault confinement rule 3, exception 1: an acknowledgement error of an
         * error-passive transmitter does not count. */
        if (!(lec == LEC_ACK && s->tec > 127)) {
            s->tec += 8;
        }
        s->tsr |= TSR_TERR(m);
        if ((s->mcr & MCR_NART) || (s->tsr & TSR_ABRQ(m))) {
            release_box(s, m, false);
        }
    }
    set_error_state(s, lec);
    /* The next try or frame: after the error frame (and the suspension of an error-passive
     * transmitter), or after the intermission already counted in the frame. */
    const int64_t gap = lec == LEC_NONE ? 0 : (14 + (s->tec > 127 ? 8 : 0)) * bit_ns(s);
    timer_mod(s->tx_timer, now_ns() + gap);
}

/* Starts the next frame when the controller is on the bus and free; or ends the one on it. */
static void tx_step(void *opaque)
{
    Stm32f4BxcanState *s = opaque;
    const int64_t now = now_ns();

    if (s->tx_box >= 0) {
        if (now < s->busy_until) {
            timer_mod(s->tx_timer, s->busy_until);
            return;
        }
        tx_done(s);
        return;
    }
    if (!on_bus(s) || bit_ns(s) == 0) {
        return; /* a mode change or the end of bus-off calls again */
    }
    const int m = next_box(s);
    if (m < 0) {
        return;
    }
    s->tx_box = m;
    s->busy_until = now + frame_bits(&s->tx[m]) * bit_ns(s);
    timer_mod(s->tx_timer, s->busy_until);
}

static void abort_box(Stm32f4BxcanState *s, int m)
{
    if (!pending(s, m)) {
        return;
    }
    if (s->tx_box == m) {
        s->tsr |= TSR_ABRQ(m); /* decided when the frame on the bus ends */
        return;
    }
    release_box(s, m, false);
    update_irqs(s);
}

/* ---- reception ---- */

static void receive_frame(Stm32f4BxcanState *s, const qemu_can_frame *f)
{
    const bool ide = f->can_id & QEMU_CAN_EFF_FLAG, rtr = f->can_id & QEMU_CAN_RTR_FLAG;
    const uint32_t id = f->can_id & (ide ? QEMU_CAN_EFF_MASK : QEMU_CAN_SFF_MASK);
    const uint32_t word = bxcan_filter_word(id, ide, rtr);

    if (s->filters.fmr & FMR_FINIT) {
        return;
    }
    const BxcanMatch hit = bxcan_filter_match(&s->filters, word);
    if (hit.fifo < 0) {
        return;
    }
    const int q = hit.fifo;
    qemu_set_irq(s->rx_out, (int)(id + 1u));
    qemu_set_irq(s->rx_out, 0);
    Mailbox mb = {
        .ir = word,
        .dtr = (uint32_t)MIN(f->can_dlc, 8) | hit.fmi << 8,
    };
    for (int i = 0; i < 4; ++i) {
        mb.dlr |= (uint32_t)f->data[i] << (8 * i);
        mb.dhr |= (uint32_t)f->data[4 + i] << (8 * i);
    }
    if (s->fmp[q] == FIFO_DEPTH) {
        s->rfr[q] |= RFR_FOVR;
        if (!(s->mcr & MCR_RFLM)) {
            s->fifo[q][FIFO_DEPTH - 1] = mb; /* the newest is overwritten */
        }
    } else {
        s->fifo[q][s->fmp[q]++] = mb;
        if (s->fmp[q] == FIFO_DEPTH) {
            s->rfr[q] |= RFR_FULL;
        }
    }
    update_irqs(s);
}

static bool bxcan_can_receive(CanBusClientState *client)
{
    return true;
}

/* A frame from another node.  The answer (> 0) is this node's acknowledgement. */
static ssize_t bxcan_receive(CanBusClientState *client, const qemu_can_frame *frames, size_t n)
{
    Stm32f4BxcanState *s = container_of(client, Stm32f4BxcanState, bus_client);
    ssize_t acked = 0;

    for (size_t i = 0; i < n; ++i) {
        const qemu_can_frame *f = &frames[i];
        if ((f->can_id & QEMU_CAN_ERR_FLAG) || (f->flags & QEMU_CAN_FRMF_TYPE_FD) || !s->rx_pin) {
            continue;
        }
        if (s->mode == MODE_SLEEP && !s->joining) {
            if (s->mcr & MCR_AWUM) {
                s->mcr &= ~MCR_SLEEP; /* the frame that wakes it is lost */
                s->msr |= MSR_WKUI;
                update_irqs(s);
                mode_step(s);
            }
            continue;
        }
        if (!on_bus(s)) {
            continue;
        }
        if (s->bus_error || !rate_matches(s)) {
            if (s->rec <= 127) {
                ++s->rec;
            }
            set_error_state(s, s->bus_error ? LEC_BIT_DOMINANT : LEC_FORM);
            continue;
        }
        if (s->rec > 127) {
            s->rec = 120;
        } else if (s->rec > 0) {
            --s->rec;
        }
        set_error_state(s, LEC_NONE);
        if (!(s->btr & BTR_SILM)) {
            acked = 1;
        }
        receive_frame(s, f);
    }
    return acked;
}

static CanBusClientInfo bxcan_bus_client_info = {
    .can_receive = bxcan_can_receive,
    .receive = bxcan_receive,
};

/* ---- registers ---- */

static uint64_t bxcan_read(void *opaque, hwaddr addr, unsigned size)
{
    Stm32f4BxcanState *s = opaque;
    switch (addr) {
    case R_MCR:
        return s->mcr;
    case R_MSR:
        return s->msr | MSR_RX | (s->tx_box >= 0 ? MSR_TXM : 0);
    case R_TSR:
        return s->tsr;
    case R_RF0R:
    case R_RF1R: {
        const int q = (addr - R_RF0R) / 4;
        return s->rfr[q] | s->fmp[q];
    }
    case R_IER:
        return s->ier;
    case R_ESR:
        return s->esr;
    case R_BTR:
        return s->btr;
    case R_TX ... R_TX + 0x2F: {
        const Mailbox *m = &s->tx[(addr - R_TX) / 16];
        const uint32_t r[4] = { m->ir, m->dtr, m->dlr, m->dhr };
        return r[(addr % 16) / 4];
    }
    case R_RX ... R_RX + 0x1F: {
        const int q = (addr - R_RX) / 16;
        static const Mailbox none;
        const Mailbox *m = s->fmp[q] ? &s->fifo[q][0] : &none;
        const uint32_t r[4] = { m->ir, m->dtr, m->dlr, m->dhr };
        return r[(addr % 16) / 4];
    }
    case R_FMR:
        return s->filters.fmr;
    case R_FM1R:
        return s->filters.fm1r;
    case R_FS1R:
        return s->filters.fs1r;
    case R_FFA1R:
        return s->filters.ffa1r;
    case R_FA1R:
        return s->filters.fa1r;
    case R_FB ... R_FB + 8 * BXCAN_FILTER_BANKS - 1:
        return s->filters.fr[(addr - R_FB) / 8][(addr % 8) / 4];
    }
    return 0;
}

static void bxcan_reset_controller(Stm32f4BxcanState *s);

static void write_mailbox(Stm32f4BxcanState *s, hwaddr addr, uint32_t v)
{
    const int m = (addr - R_TX) / 16, reg = (addr % 16) / 4;
    Mailbox *mb = &s->tx[m];
    if (!(s->tsr & TSR_TME(m))) {
        qemu_log_mask(LOG_GUEST_ERROR, "stm32f4-bxcan: mailbox %d written while pending: ignored\n", m);
        return;
    }
    switch (reg) {
    case 0:
        mb->ir = v;
        if (v & TIR_TXRQ) {
            s->tsr &= ~(TSR_TME(m) | TSR_RQCP(m) | TSR_TXOK(m) | TSR_ALST(m) | TSR_TERR(m));
            s->tx_order[m] = s->tx_seq++;
            update_tsr_code(s);
            update_irqs(s);
            if (s->tx_box < 0) {
                timer_mod(s->tx_timer, now_ns());
            }
        }
        break;
    case 1:
        mb->dtr = v & 0xFFFF010F;
        break;
    case 2:
        mb->dlr = v;
        break;
    case 3:
        mb->dhr = v;
        break;
    }
}

static void write_filter_reg(Stm32f4BxcanState *s, hwaddr addr, uint32_t v)
{
    BxcanFilters *f = &s->filters;
    const bool finit = f->fmr & FMR_FINIT;
    switch (addr) {
    case R_FMR:
        f->fmr = v & (0x3F00 | FMR_FINIT);
        return;
    case R_FM1R:
    case R_FS1R:
    case R_FFA1R:
        if (!finit) {
            qemu_log_mask(LOG_GUEST_ERROR, "stm32f4-bxcan: filter configuration written outside "
                          "filter initialisation (FINIT): ignored\n");
            return;
        }
        *(addr == R_FM1R ? &f->fm1r : addr == R_FS1R ? &f->fs1r : &f->ffa1r) = v & 0x0FFFFFFF;
        return;
    case R_FA1R:
        f->fa1r = v & 0x0FFFFFFF;
        return;
    default: {
        const int bank = (addr - R_FB) / 8;
        if (!finit && ((f->fa1r >> bank) & 1)) {
            qemu_log_mask(LOG_GUEST_ERROR, "stm32f4-bxcan: active filter bank %d written outside "
                          "FINIT: ignored\n", bank);
            return;
        }
        f->fr[bank][(addr % 8) / 4] = v;
    }
    }
}

static void bxcan_write(void *opaque, hwaddr addr, uint64_t val, unsigned size)
{
    Stm32f4BxcanState *s = opaque;
    const uint32_t v = val;

    switch (addr) {
    case R_MCR:
        if (v & MCR_RESET) {
            bxcan_reset_controller(s);
            return;
        }
        if (v & MCR_TTCM) {
            qemu_log_mask(LOG_UNIMP, "stm32f4-bxcan: time-triggered mode not modelled\n");
        }
        s->mcr = v & 0x100FF;
        mode_step(s);
        return;
    case R_MSR:
        s->msr &= ~(v & (MSR_ERRI | MSR_WKUI | MSR_SLAKI));
        update_irqs(s);
        return;
    case R_TSR:
        for (int m = 0; m < 3; ++m) {
            if (v & TSR_RQCP(m)) {
                s->tsr &= ~(TSR_RQCP(m) | TSR_TXOK(m) | TSR_ALST(m) | TSR_TERR(m));
            }
            if (v & TSR_ABRQ(m)) {
                abort_box(s, m);
            }
        }
        update_irqs(s);
        return;
    case R_RF0R:
    case R_RF1R: {
        const int q = (addr - R_RF0R) / 4;
        s->rfr[q] &= ~(v & (RFR_FULL | RFR_FOVR));
        if ((v & RFR_RFOM) && s->fmp[q]) {
            memmove(&s->fifo[q][0], &s->fifo[q][1], (FIFO_DEPTH - 1) * sizeof(Mailbox));
            --s->fmp[q];
        }
        update_irqs(s);
        return;
    }
    case R_IER:
        s->ier = v & 0x38F7F;
        update_irqs(s);
        return;
    case R_ESR:
        s->esr = (s->esr & ~0x70u) | (v & 0x70u); /* LEC is writable (to 7, to see it change) */
        return;
    case R_BTR:
        if (s->mode != MODE_INIT) {
            qemu_log_mask(LOG_GUEST_ERROR, "stm32f4-bxcan: BTR written outside initialisation: ignored\n");
            return;
        }
        s->btr = v & 0xC37F03FF;
        return;
    case R_TX ... R_TX + 0x2F:
        write_mailbox(s, addr, v);
        return;
    case R_RX ... R_RX + 0x1F:
        return;
    case R_FMR ... R_FB + 8 * BXCAN_FILTER_BANKS - 1:
        write_filter_reg(s, addr, v);
        return;
    }
    qemu_log_mask(LOG_GUEST_ERROR, "stm32f4-bxcan: write to 0x%" HWADDR_PRIx "\n", addr);
}

static const MemoryRegionOps bxcan_ops = {
    .read = bxcan_read,
    .write = bxcan_write,
    .endianness = DEVICE_LITTLE_ENDIAN,
    .valid = { .min_access_size = 4, .max_access_size = 4 },
};

/* ---- lines ---- */

static void rx_af_in(void *opaque, int n, int level)
{
    STM32F4_BXCAN(opaque)->rx_pin = level == PIN_AF;
}

static void tx_af_in(void *opaque, int n, int level)
{
    STM32F4_BXCAN(opaque)->tx_pin = level == PIN_AF;
}

static void bus_error_in(void *opaque, int n, int level)
{
    Stm32f4BxcanState *s = opaque;
    s->bus_error = level != 0;
}

/* ---- reset and realisation ---- */

/* The controller (not the filters) to its reset state: sleep. */
static void bxcan_reset_controller(Stm32f4BxcanState *s)
{
    timer_del(s->mode_timer);
    timer_del(s->tx_timer);
    timer_del(s->boff_timer);
    s->mcr = MCR_DBF | MCR_SLEEP;
    s->msr = MSR_SAMP | MSR_RX;
    s->tsr = TSR_TME(0) | TSR_TME(1) | TSR_TME(2);
    s->rfr[0] = s->rfr[1] = 0;
    s->fmp[0] = s->fmp[1] = 0;
    s->ier = 0;
    s->esr = 0;
    s->btr = 0x01230000;
    memset(s->tx, 0, sizeof s->tx);
    memset(s->fifo, 0, sizeof s->fifo);
    s->tec = s->rec = 0;
    s->mode = MODE_SLEEP;
    s->joining = false;
    s->recovering = false;
    s->tx_box = -1;
    s->busy_until = 0;
    update_msr_mode(s);
    update_tsr_code(s);
    update_irqs(s);
}

static void bxcan_reset(DeviceState *dev)
{
    Stm32f4BxcanState *s = STM32F4_BXCAN(dev);
    bxcan_reset_controller(s);
    memset(&s->filters, 0, sizeof s->filters);
    s->filters.fmr = 0x2A1C0E01;
}

static void bxcan_realize(DeviceState *dev, Error **errp)
{
    Stm32f4BxcanState *s = STM32F4_BXCAN(dev);
    s->mode_timer = timer_new_ns(QEMU_CLOCK_VIRTUAL, mode_step, s);
    s->tx_timer = timer_new_ns(QEMU_CLOCK_VIRTUAL, tx_step, s);
    s->boff_timer = timer_new_ns(QEMU_CLOCK_VIRTUAL, boff_recovered, s);
    s->bus_client.info = &bxcan_bus_client_info;
    if (s->canbus) {
        can_bus_insert_client(s->canbus, &s->bus_client);
    }
}

static void bxcan_init(Object *obj)
{
    Stm32f4BxcanState *s = STM32F4_BXCAN(obj);
    DeviceState *dev = DEVICE(obj);
    memory_region_init_io(&s->iomem, obj, &bxcan_ops, s, "stm32f4-bxcan", 0x400);
    sysbus_init_mmio(SYS_BUS_DEVICE(obj), &s->iomem);
    for (int i = 0; i < 4; ++i) {
        sysbus_init_irq(SYS_BUS_DEVICE(obj), &s->irq[i]);
    }
    s->pclk = qdev_init_clock_in(dev, "pclk", NULL, NULL, 0);
    qdev_init_gpio_in_named(dev, rx_af_in, BXCAN_IN_RX_AF, 1);
    qdev_init_gpio_in_named(dev, tx_af_in, BXCAN_IN_TX_AF, 1);
    qdev_init_gpio_in_named(dev, bus_error_in, BXCAN_IN_BUS_ERROR, 1);
    qdev_init_gpio_out_named(dev, &s->rx_out, BXCAN_OUT_RX, 1);
}

static Property bxcan_properties[] = {
    DEFINE_PROP_UINT32("bus-bitrate", Stm32f4BxcanState, bus_bitrate, 500000),
    DEFINE_PROP_LINK("canbus", Stm32f4BxcanState, canbus, TYPE_CAN_BUS, CanBusState *),
    DEFINE_PROP_END_OF_LIST(),
};

static void bxcan_class_init(ObjectClass *klass, void *data)
{
    DeviceClass *dc = DEVICE_CLASS(klass);
    dc->realize = bxcan_realize;
    dc->reset = bxcan_reset;
    device_class_set_props(dc, bxcan_properties);
}

static const TypeInfo bxcan_info = {
    .name = TYPE_STM32F4_BXCAN,
    .parent = TYPE_SYS_BUS_DEVICE,
    .instance_size = sizeof(Stm32f4BxcanState),
    .instance_init = bxcan_init,
    .class_init = bxcan_class_init,
};

static void bxcan_register_types(void)
{
    type_register_static(&bxcan_info);
}

type_init(bxcan_register_types)
