/* bxCAN of the STM32F405/407 (RM0090 section 32, register map 32.9.5): control and status,
 * the three transmit mailboxes, the two receive FIFOs' output mailboxes and the 28 filter banks
 * that CAN1 and CAN2 share (they live in CAN1's block).  Our own definitions; only the bits the
 * driver uses are named. */
#ifndef TSE_REGS_CAN_H
#define TSE_REGS_CAN_H

#include <stddef.h>
#include <stdint.h>

#define TSE_CAN1_BASE 0x40006400u
#define BXCAN_FILTER_BANKS 28u

typedef struct {
    volatile uint32_t TIR;  /* identifier and transmit request */
    volatile uint32_t TDTR; /* length (DLC) and time stamp */
    volatile uint32_t TDLR; /* data bytes 0..3, byte 0 in bits 7:0 */
    volatile uint32_t TDHR; /* data bytes 4..7 */
} tse_can_tx_mailbox;

typedef struct {
    volatile uint32_t RIR;
    volatile uint32_t RDTR; /* length (DLC), matching filter index, time stamp */
    volatile uint32_t RDLR;
    volatile uint32_t RDHR;
} tse_can_rx_mailbox;

typedef struct {
    volatile uint32_t FR1;
    volatile uint32_t FR2;
} tse_can_filter_bank;

typedef struct {
    volatile uint32_t MCR;  /* 0x000 master control */
    volatile uint32_t MSR;  /* 0x004 master status */
    volatile uint32_t TSR;  /* 0x008 transmit status */
    volatile uint32_t RF0R; /* 0x00C receive FIFO 0 */
    volatile uint32_t RF1R; /* 0x010 receive FIFO 1 */
    volatile uint32_t IER;  /* 0x014 interrupt enable */
    volatile uint32_t ESR;  /* 0x018 error status */
    volatile uint32_t BTR;  /* 0x01C bit timing (writable in initialisation mode only) */
    uint32_t reserved0[88]; /* 0x020..0x17F */
    tse_can_tx_mailbox TX[3];  /* 0x180, 0x190, 0x1A0 */
    tse_can_rx_mailbox RX[2];  /* 0x1B0 (FIFO 0), 0x1C0 (FIFO 1) */
    uint32_t reserved1[12]; /* 0x1D0..0x1FF */
    volatile uint32_t FMR;   /* 0x200 filter master */
    volatile uint32_t FM1R;  /* 0x204 filter mode: bit n set = bank n in identifier-list mode */
    uint32_t reserved2;      /* 0x208 */
    volatile uint32_t FS1R;  /* 0x20C filter scale: bit n set = bank n is one 32-bit filter */
    uint32_t reserved3;      /* 0x210 */
    volatile uint32_t FFA1R; /* 0x214 FIFO assignment: bit n set = bank n feeds FIFO 1 */
    uint32_t reserved4;      /* 0x218 */
    volatile uint32_t FA1R;  /* 0x21C filter activation: bit n set = bank n active */
    uint32_t reserved5[8];   /* 0x220..0x23F */
    tse_can_filter_bank FB[BXCAN_FILTER_BANKS]; /* 0x240..0x31F */
} tse_can_regs;

_Static_assert(offsetof(tse_can_regs, MSR) == 0x004, "CAN MSR offset");
_Static_assert(offsetof(tse_can_regs, TSR) == 0x008, "CAN TSR offset");
_Static_assert(offsetof(tse_can_regs, RF0R) == 0x00C, "CAN RF0R offset");
_Static_assert(offsetof(tse_can_regs, RF1R) == 0x010, "CAN RF1R offset");
_Static_assert(offsetof(tse_can_regs, IER) == 0x014, "CAN IER offset");
_Static_assert(offsetof(tse_can_regs, ESR) == 0x018, "CAN ESR offset");
_Static_assert(offsetof(tse_can_regs, BTR) == 0x01C, "CAN BTR offset");
_Static_assert(offsetof(tse_can_regs, TX[0].TIR) == 0x180, "CAN TI0R offset");
_Static_assert(offsetof(tse_can_regs, TX[1].TIR) == 0x190, "CAN TI1R offset");
_Static_assert(offsetof(tse_can_regs, TX[2].TDHR) == 0x1AC, "CAN TDH2R offset");
_Static_assert(offsetof(tse_can_regs, RX[0].RIR) == 0x1B0, "CAN RI0R offset");
_Static_assert(offsetof(tse_can_regs, RX[1].RDHR) == 0x1CC, "CAN RDH1R offset");
_Static_assert(offsetof(tse_can_regs, FMR) == 0x200, "CAN FMR offset");
_Static_assert(offsetof(tse_can_regs, FM1R) == 0x204, "CAN FM1R offset");
_Static_assert(offsetof(tse_can_regs, FS1R) == 0x20C, "CAN FS1R offset");
_Static_assert(offsetof(tse_can_regs, FFA1R) == 0x214, "CAN FFA1R offset");
_Static_assert(offsetof(tse_can_regs, FA1R) == 0x21C, "CAN FA1R offset");
_Static_assert(offsetof(tse_can_regs, FB[0].FR1) == 0x240, "CAN F0R1 offset");
_Static_assert(offsetof(tse_can_regs, FB[27].FR2) == 0x31C, "CAN F27R2 offset");
_Static_assert(sizeof(tse_can_regs) == 0x320, "CAN block size");

#define TSE_CAN1 ((tse_can_regs *)TSE_CAN1_BASE)

/* MCR.  Reset value 0x00010002: SLEEP and DBF set. */
#define CAN_MCR_INRQ (1u << 0)  /* request initialisation mode */
#define CAN_MCR_SLEEP (1u << 1) /* request sleep mode */
#define CAN_MCR_TXFP (1u << 2)  /* transmit priority by request order, not by identifier */
#define CAN_MCR_RFLM (1u << 3)
#define CAN_MCR_NART (1u << 4)
#define CAN_MCR_AWUM (1u << 5)  /* leave sleep on bus activity by hardware */
#define CAN_MCR_ABOM (1u << 6)  /* leave bus-off by hardware after 128 x 11 recessive bits */
#define CAN_MCR_TTCM (1u << 7)
#define CAN_MCR_RESET (1u << 15)
#define CAN_MCR_DBF (1u << 16)  /* freeze the controller while the core is halted by a debugger */

/* MSR.  ERRI, WKUI and SLAKI are cleared by writing 1. */
#define CAN_MSR_INAK (1u << 0)
#define CAN_MSR_SLAK (1u << 1)
#define CAN_MSR_ERRI (1u << 2)
#define CAN_MSR_WKUI (1u << 3)
#define CAN_MSR_SLAKI (1u << 4)

/* TSR, per mailbox m = 0..2.  Writing 1 to RQCPm clears RQCPm, TXOKm, ALSTm and TERRm;
 * writing 1 to ABRQm aborts the mailbox, so the driver never writes ABRQ bits. */
#define CAN_TSR_RQCP(m) (1u << (8u * (m)))
#define CAN_TSR_TXOK(m) (2u << (8u * (m)))
#define CAN_TSR_ALST(m) (4u << (8u * (m)))
#define CAN_TSR_TERR(m) (8u << (8u * (m)))
#define CAN_TSR_ABRQ(m) (0x80u << (8u * (m)))
#define CAN_TSR_RQCP_ALL (CAN_TSR_RQCP(0) | CAN_TSR_RQCP(1) | CAN_TSR_RQCP(2))
#define CAN_TSR_TME(m) (1u << (26u + (m)))
#define CAN_TSR_TME_ALL (CAN_TSR_TME(0) | CAN_TSR_TME(1) | CAN_TSR_TME(2))

/* RF0R/RF1R.  FULL and FOVR are cleared by writing 1; RFOM releases the output mailbox. */
#define CAN_RFR_FMP_MASK 0x3u
#define CAN_RFR_FULL (1u << 3)
#define CAN_RFR_FOVR (1u << 4)
#define CAN_RFR_RFOM (1u << 5)

/* IER */
#define CAN_IER_TMEIE (1u << 0)  /* TX interrupt on any RQCPm */
#define CAN_IER_FMPIE0 (1u << 1) /* RX0 interrupt while FIFO 0 holds a message */
#define CAN_IER_FFIE0 (1u << 2)
#define CAN_IER_FOVIE0 (1u << 3)
#define CAN_IER_EWGIE (1u << 8)
#define CAN_IER_EPVIE (1u << 9)
#define CAN_IER_BOFIE (1u << 10)
#define CAN_IER_LECIE (1u << 11)
#define CAN_IER_ERRIE (1u << 15) /* SCE interrupt on ERRI */

/* ESR */
#define CAN_ESR_EWGF (1u << 0)
#define CAN_ESR_EPVF (1u << 1)
#define CAN_ESR_BOFF (1u << 2)
#define CAN_ESR_LEC_SHIFT 4u
#define CAN_ESR_TEC_SHIFT 16u
#define CAN_ESR_REC_SHIFT 24u

/* BTR: every timing field holds its value minus one. */
#define CAN_BTR_BRP_SHIFT 0u
#define CAN_BTR_BRP_MASK 0x3FFu
#define CAN_BTR_TS1_SHIFT 16u
#define CAN_BTR_TS1_MASK 0xFu
#define CAN_BTR_TS2_SHIFT 20u
#define CAN_BTR_TS2_MASK 0x7u
#define CAN_BTR_SJW_SHIFT 24u
#define CAN_BTR_SJW_MASK 0x3u
#define CAN_BTR_LBKM (1u << 30)
#define CAN_BTR_SILM (1u << 31)

/* TIxR / RIxR */
#define CAN_TIR_TXRQ (1u << 0)
#define CAN_IR_RTR (1u << 1)
#define CAN_IR_IDE (1u << 2)
#define CAN_IR_EXID_SHIFT 3u
#define CAN_IR_STID_SHIFT 21u
#define CAN_IR_STID_MASK 0x7FFu

/* TDTxR / RDTxR */
#define CAN_DTR_DLC_MASK 0xFu

/* FMR.  Reset value 0x2A1C0E01: FINIT set, CAN2SB = 14 (banks 0..13 belong to CAN1). */
#define CAN_FMR_FINIT (1u << 0)
#define CAN_FMR_CAN2SB_SHIFT 8u
#define CAN_FMR_CAN2SB_MASK 0x3Fu

/* Layout of one 16-bit filter (a half of FxR1 or FxR2): STID[10:0] in 15:5, RTR in 4, IDE in 3,
 * EXID[17:15] in 2:0.  In 16-bit mask mode FxR1 holds filter 2n (identifier in 15:0, mask in
 * 31:16) and FxR2 filter 2n+1. */
#define CAN_F16_STID_SHIFT 5u
#define CAN_F16_RTR (1u << 4)
#define CAN_F16_IDE (1u << 3)

#endif
