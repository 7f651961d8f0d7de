/* The bxCAN1 driver: initialisation, the three interrupt entry points and hal_can.  See bxcan.h
 * for what it promises and expects.
 *
 * Concurrency.  The tx ring has one producer, send(), and two would-be consumers: the TX
 * interrupt and send()'s kick (needed because the TX interrupt only fires when a transmission
 * completes, so an idle controller must be started from thread code).  They are made exclusive
 * without the board's help:
 * - the kick clears IER.TMEIE before it touches the ring or the mailboxes, and restores it after;
 * - bxcan_tx_isr does nothing while TMEIE is clear.
 * On one core an interrupt cannot be preempted by thread code, so the only overlap possible is
 * the TX interrupt entering during the kick; once TMEIE is clear (the store is ordered before the
 * interrupt's read of IER: same core, same device), such an entry returns at once.  The TX
 * interrupt line is TMEIE & (RQCP0 | RQCP1 | RQCP2): a transmission completing during the kick
 * leaves its RQCP set, and restoring TMEIE raises the interrupt again, so no completion is lost.
 * Only thread code writes IER after init, so the kick's read-modify-write is not racy. */
#include "hal_stm32f4/bxcan.h"

#include <stddef.h>
#include <string.h>

#include "hal_stm32f4/bxcan_filter.h"
#include "hal_stm32f4/bxcan_timing.h"

#define MCR_RUN (CAN_MCR_DBF | CAN_MCR_ABOM | CAN_MCR_AWUM | CAN_MCR_TXFP)
#define IER_RUN (CAN_IER_TMEIE | CAN_IER_FMPIE0 | CAN_IER_EPVIE | CAN_IER_BOFIE | CAN_IER_ERRIE)
#define FIFO_DEPTH 3u

/* A counter with a single writer: load and store, no read-modify-write needed. */
static void bump(_Atomic uint32_t *c)
{
    atomic_store_explicit(c, atomic_load_explicit(c, memory_order_relaxed) + 1u,
                          memory_order_relaxed);
}

/* Polls until (MSR & mask) == want, calling idle between polls.  False on timeout. */
static bool wait_msr(tse_can_regs *r, uint32_t mask, uint32_t want, void (*idle)(void))
{
    for (uint32_t n = 0; n < BXCAN_WAIT_LOOPS; ++n) {
        if ((r->MSR & mask) == want)
            return true;
        if (idle)
            idle();
    }
    return false;
}

/* Filter banks are written with FINIT set and each bank inactive while it changes (RM0090
 * 32.7.4); CAN2's banks (14..27) are left as they are. */
static void install_filters(tse_can_regs *r, const bxcan_filter_regs *f)
{
    const uint32_t ours = (1u << BXCAN_CAN1_BANKS) - 1u;
    r->FMR |= CAN_FMR_FINIT;
    r->FA1R &= ~ours;
    r->FM1R = (r->FM1R & ~ours) | f->fm1r;
    r->FS1R = (r->FS1R & ~ours) | f->fs1r;
    r->FFA1R = (r->FFA1R & ~ours) | f->ffa1r;
    for (uint32_t b = 0; b < BXCAN_CAN1_BANKS; ++b) {
        if (f->fa1r & (1u << b)) {
            r->FB[b].FR1 = f->fr1[b];
            r->FB[b].FR2 = f->fr2[b];
        }
    }
    r->FA1R = (r->FA1R & ~ours) | f->fa1r;
    r->FMR &= ~CAN_FMR_FINIT;
}

static void reset_dev(bxcan_dev *dev, tse_can_regs *regs)
{
    dev->regs = regs;
    can_ring_init(&dev->rx);
    can_ring_init(&dev->tx);
    atomic_init(&dev->rx_overruns, 0u);
    atomic_init(&dev->bus_off_events, 0u);
    dev->boff_seen = false;
}

bxcan_status bxcan_init(bxcan_dev *dev, tse_can_regs *regs, uint32_t pclk_hz, uint32_t bitrate,
                        uint8_t node, void (*idle)(void))
{
    uint32_t btr;
    bxcan_filter_regs filter;
    reset_dev(dev, regs);
    if (bxcan_timing_compute(pclk_hz, bitrate, &btr) != BXCAN_TIMING_OK)
        return BXCAN_ERR_TIMING;
    if (bxcan_filter_for_node(node, &filter) != 0)
        return BXCAN_ERR_NODE;
    /* Out of sleep (the reset state) and into initialisation: BTR is writable only there. */
    regs->MCR = CAN_MCR_DBF | CAN_MCR_INRQ;
    if (!wait_msr(regs, CAN_MSR_INAK, CAN_MSR_INAK, idle))
        return BXCAN_ERR_ENTER_INIT;
    if (!wait_msr(regs, CAN_MSR_SLAK, 0u, idle))
        return BXCAN_ERR_WAKE;
    regs->MCR = MCR_RUN | CAN_MCR_INRQ;
    regs->BTR = btr;
    install_filters(regs, &filter);
    regs->IER = IER_RUN;
    regs->MCR = MCR_RUN; /* leave initialisation: joins the bus after 11 recessive bits */
    if (!wait_msr(regs, CAN_MSR_INAK, 0u, idle))
        return BXCAN_ERR_LEAVE_INIT;
    return BXCAN_OK;
}

const char *bxcan_status_str(bxcan_status s)
{
    switch (s) {
    case BXCAN_OK:
        return "ok";
    case BXCAN_ERR_TIMING:
        return "no exact bit timing";
    case BXCAN_ERR_NODE:
        return "node outside 1..15";
    case BXCAN_ERR_ENTER_INIT:
        return "INAK never set (entering initialisation)";
    case BXCAN_ERR_WAKE:
        return "SLAK never cleared (leaving sleep)";
    case BXCAN_ERR_LEAVE_INIT:
        return "INAK never cleared (bus never idle)";
    }
    return "?";
}

/* ---- reception ---- */

static uint32_t pack4(const uint8_t *d)
{
    return (uint32_t)d[0] | (uint32_t)d[1] << 8 | (uint32_t)d[2] << 16 | (uint32_t)d[3] << 24;
}

static void unpack4(uint32_t w, uint8_t *d)
{
    for (unsigned i = 0; i < 4; ++i)
        d[i] = (uint8_t)(w >> (8u * i));
}

/* The output mailbox of FIFO 0 into the rx ring. */
static void take_frame(bxcan_dev *dev, const tse_can_rx_mailbox *mb)
{
    const uint32_t rir = mb->RIR;
    if (rir & (CAN_IR_IDE | CAN_IR_RTR))
        return; /* the filter admits neither; never hand one to the firmware */
    hal_can_frame f;
    const uint32_t dlc = mb->RDTR & CAN_DTR_DLC_MASK;
    f.id = (uint16_t)(rir >> CAN_IR_STID_SHIFT & CAN_IR_STID_MASK);
    f.len = (uint8_t)(dlc > 8u ? 8u : dlc); /* DLC 9..15 means 8 bytes in classic CAN */
    unpack4(mb->RDLR, f.data);
    unpack4(mb->RDHR, f.data + 4);
    memset(f.data + f.len, 0, sizeof f.data - f.len);
    if (!can_ring_push(&dev->rx, &f))
        bump(&dev->rx_overruns);
}

/* Drains FIFO 0: at most its depth per call (bounded whatever the register reads; frames that
 * arrive meanwhile keep the interrupt pending).  One write per release, which also acknowledges
 * an overrun: FOVR means the hardware dropped at least one frame (it cannot say how many), and
 * counts one. */
void bxcan_rx0_isr(bxcan_dev *dev)
{
    tse_can_regs *r = dev->regs;
    for (uint32_t n = 0; n < FIFO_DEPTH; ++n) {
        const uint32_t rf = r->RF0R;
        if ((rf & CAN_RFR_FMP_MASK) == 0)
            break;
        take_frame(dev, &r->RX[0]);
        if (rf & CAN_RFR_FOVR)
            bump(&dev->rx_overruns);
        r->RF0R = CAN_RFR_RFOM | (rf & (CAN_RFR_FULL | CAN_RFR_FOVR));
    }
}

/* ---- transmission ---- */

static void load_mailbox(tse_can_tx_mailbox *mb, const hal_can_frame *f)
{
    uint8_t d[8] = {0};
    const uint8_t len = f->len > 8u ? 8u : f->len;
    memcpy(d, f->data, len);
    mb->TDTR = len;
    mb->TDLR = pack4(d);
    mb->TDHR = pack4(d + 4);
    /* Last: setting TXRQ hands the mailbox to the hardware. */
    mb->TIR = (uint32_t)(f->id & CAN_IR_STID_MASK) << CAN_IR_STID_SHIFT | CAN_TIR_TXRQ;
}

/* Acknowledges completed requests and loads every empty mailbox from the tx ring, in mailbox
 * order; with TXFP the hardware sends them in the order loaded.  TSR is read once: a mailbox
 * empty then stays empty until loaded here, and one emptied later raises its RQCP again. */
static void refill(bxcan_dev *dev)
{
    tse_can_regs *r = dev->regs;
    const uint32_t tsr = r->TSR;
    if (tsr & CAN_TSR_RQCP_ALL)
        r->TSR = tsr & CAN_TSR_RQCP_ALL; /* write 1 to clear; never the ABRQ bits */
    for (uint32_t m = 0; m < 3u; ++m) {
        hal_can_frame f;
        if (!(tsr & CAN_TSR_TME(m)))
            continue;
        if (!can_ring_pop(&dev->tx, &f))
            break;
        load_mailbox(&r->TX[m], &f);
    }
}

void bxcan_tx_isr(bxcan_dev *dev)
{
    if (!(dev->regs->IER & CAN_IER_TMEIE))
        return; /* send()'s kick owns the mailboxes (see the top of this file) */
    refill(dev);
}

/* Thread code: refill with the TX interrupt held off at the peripheral. */
static void kick(bxcan_dev *dev)
{
    tse_can_regs *r = dev->regs;
    const uint32_t ier = r->IER;
    r->IER = ier & ~CAN_IER_TMEIE;
    (void)r->IER; /* read back: the store has reached the peripheral */
    refill(dev);
    r->IER = ier;
}

/* ---- errors ---- */

/* Counts entries into bus-off.  The interrupt comes from ERRI, raised when EPVF or BOFF gets set;
 * acknowledging first means a later change raises it again, and counting only a 0 -> 1 change
 * of BOFF as seen here keeps that second entry from counting the same bus-off twice.  Between
 * two bus-offs the controller recovers (TEC = 0) and passes error-passive again, whose interrupt
 * sees BOFF clear. */
void bxcan_sce_isr(bxcan_dev *dev)
{
    tse_can_regs *r = dev->regs;
    r->MSR = CAN_MSR_ERRI;
    const bool boff = (r->ESR & CAN_ESR_BOFF) != 0;
    if (boff && !dev->boff_seen)
        bump(&dev->bus_off_events);
    dev->boff_seen = boff;
}

/* ---- hal_can ---- */

static int can_send(void *ctx, const hal_can_frame *f)
{
    bxcan_dev *dev = ctx;
    const bool queued = can_ring_push(&dev->tx, f);
    kick(dev);
    return queued ? 0 : -1;
}

static int can_receive(void *ctx, hal_can_frame *f)
{
    bxcan_dev *dev = ctx;
    return can_ring_pop(&dev->rx, f) ? 1 : 0;
}

static void can_state(void *ctx, hal_can_state *st)
{
    bxcan_dev *dev = ctx;
    const uint32_t esr = dev->regs->ESR;
    const uint32_t events = atomic_load_explicit(&dev->bus_off_events, memory_order_relaxed);
    st->tx_errors = (uint8_t)(esr >> CAN_ESR_TEC_SHIFT);
    st->rx_errors = (uint8_t)(esr >> CAN_ESR_REC_SHIFT);
    st->error_passive = (esr & CAN_ESR_EPVF) != 0;
    st->bus_off = (esr & CAN_ESR_BOFF) != 0;
    st->bus_off_events = events; /* a bus-off already recovered still counts here */
    st->rx_overruns = atomic_load_explicit(&dev->rx_overruns, memory_order_relaxed);
}

hal_can bxcan_hal(bxcan_dev *dev)
{
    const hal_can h = {dev, can_send, can_receive, can_state};
    return h;
}
