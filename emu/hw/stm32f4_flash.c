/*
 * STM32F405/407 embedded flash: the 1 MiB array (sectors 0..3 of 16 KiB, 4 of 64 KiB, 5..11 of
 * 128 KiB) and its interface (RM0090 section 3), backed by a file so that what was programmed
 * is there when the emulator starts again.
 *
 * Modelled:
 * - ACR: wait states, prefetch and cache enables as written; too few wait states for HCLK
 *   (RM0090 table 10, 2.7..3.6 V: one per 30 MHz) is reported as a guest error.
 * - The unlock sequence: KEY1 then KEY2 clears CR.LOCK; any other write to KEYR (a wrong key,
 *   the keys out of order, a key while CR is unlocked) is a bus error and CR stays locked until
 *   the next reset.  Setting CR.LOCK locks it again.
 * - Sector erase (SER, SNB, STRT) and mass erase (MER): BSY for the datasheet's typical time at
 *   the PSIZE chosen (16/64/128 KiB: 250/550/1000 ms at x32, 400/1200/2000 ms at x8), then the
 *   sector reads 0xFF and EOP is set.
 * - Programming (PG): a store into the array while PG is set is BSY for 16 us, then the word
 *   holds old AND new: programming only clears bits (RM0090 3.5.4), so programming a word that
 *   is not erased leaves bits that should have risen at 0 and the read-back differs.  A store
 *   whose size is not PSIZE's sets PGPERR, a misaligned one PGAERR, a store without PG (or
 *   while CR is locked) PGSERR; none of them programs.  A store or a CR write while BSY
 *   waits for the operation to end, as the part stalls the bus (here: the operation completes
 *   at once).
 * - SR: EOP and the error flags are cleared by writing 1; the flash interrupt (EOPIE, ERRIE).
 * - A reset (power cut, watchdog) during an erase leaves the sector partly erased: the part
 *   of it in proportion to the time elapsed reads 0xFF, the rest keeps its old contents; a
 *   program cut short programs nothing.
 * Not modelled: the CPU stall on fetches while BSY (code keeps running from flash), the ART
 * caches' contents (reads always see the array), option bytes (OPTCR reads its reset value and
 * ignores writes), write protection, OTP, the read-out protection, wear.
 *
 * SPDX-License-Identifier: GPL-2.0-or-later
 */
#include "qemu/osdep.h"
#include "qemu/log.h"
#include "qemu/error-report.h"
#include "qemu/timer.h"
#include "qapi/error.h"
#include "hw/sysbus.h"
#include "hw/irq.h"
#include "hw/qdev-clock.h"
#include "hw/qdev-properties.h"
#include "exec/memory.h"
#include "tse_f407.h"

OBJECT_DECLARE_SIMPLE_TYPE(Stm32f4FlashState, STM32F4_FLASH)

#define FLASH_BYTES (1024 * 1024)
#define NUM_SECTORS 12

#define R_ACR 0x00
#define R_KEYR 0x04
#define R_OPTKEYR 0x08
#define R_SR 0x0C
#define R_CR 0x10
#define R_OPTCR 0x14

#define KEY1 0x45670123u
#define KEY2 0xCDEF89ABu

#define SR_EOP (1u << 0)
#define SR_OPERR (1u << 1)
#define SR_WRPERR (1u << 4)
#define SR_PGAERR (1u << 5)
#define SR_PGPERR (1u << 6)
#define SR_PGSERR (1u << 7)
#define SR_BSY (1u << 16)
#define SR_ERRORS (SR_OPERR | SR_WRPERR | SR_PGAERR | SR_PGPERR | SR_PGSERR)

#define CR_PG (1u << 0)
#define CR_SER (1u << 1)
#define CR_MER (1u << 2)
#define CR_SNB_SHIFT 3
#define CR_PSIZE_SHIFT 8
#define CR_STRT (1u << 16)
#define CR_EOPIE (1u << 24)
#define CR_ERRIE (1u << 25)
#define CR_LOCK (1u << 31)
#define CR_WRITABLE (CR_PG | CR_SER | CR_MER | (0xFu << CR_SNB_SHIFT) | (3u << CR_PSIZE_SHIFT) | \
                     CR_EOPIE | CR_ERRIE)

#define PROGRAM_NS 16000

enum { OP_NONE, OP_ERASE, OP_PROGRAM };

struct Stm32f4FlashState {
    SysBusDevice parent_obj;
    MemoryRegion iomem;
    MemoryRegion array;
    uint8_t *mem;
    qemu_irq irq;
    qemu_irq op_out; /* FLASH_OUT_OP */
    Clock *hclk;
    QEMUTimer *timer;
    uint32_t acr, sr, cr;
    int key_state;      /* 0: expecting KEY1, 1: expecting KEY2 */
    bool locked_hard;   /* a wrong key: locked until reset */
    /* the operation in progress (BSY) */
    int op;
    int64_t op_start, op_end;
    uint32_t op_addr, op_len, op_data, op_size;
    int fd;
    /* properties */
    char *file;
};

static const uint32_t sector_base[NUM_SECTORS + 1] = {
    0x00000, 0x04000, 0x08000, 0x0C000, 0x10000, 0x20000, 0x40000,
    0x60000, 0x80000, 0xA0000, 0xC0000, 0xE0000, 0x100000,
};

static void update_irq(Stm32f4FlashState *s)
{
    const bool eop = (s->sr & SR_EOP) && (s->cr & CR_EOPIE);
    const bool err = (s->sr & SR_OPERR) && (s->cr & CR_ERRIE);
    qemu_set_irq(s->irq, eop || err);
}

static void store(Stm32f4FlashState *s, uint32_t off, uint32_t len)
{
    memory_region_flush_rom_device(&s->array, off, len);
    if (s->fd >= 0 && pwrite(s->fd, s->mem + off, len, off) != (ssize_t)len) {
        error_report("stm32f4-flash: writing %s: %s", s->file, strerror(errno));
    }
}

/* Applies the operation in progress, all of it (done) or the part done by now (cut). */
static void finish_op(Stm32f4FlashState *s, bool cut)
{
    if (s->op == OP_ERASE) {
        uint32_t len = s->op_len;
        if (cut) {
            const int64_t now = qemu_clock_get_ns(QEMU_CLOCK_VIRTUAL);
            const double done = (double)(now - s->op_start) / (double)(s->op_end - s->op_start);
            len = (uint32_t)(done < 0 ? 0 : done > 1 ? len : done * len) & ~3u;
        }
        memset(s->mem + s->op_addr, 0xFF, len);
        store(s, s->op_addr, len);
    } else if (s->op == OP_PROGRAM && !cut) {
        for (uint32_t i = 0; i < s->op_size; ++i) {
            s->mem[s->op_addr + i] &= (uint8_t)(s->op_data >> (8 * i));
        }
        store(s, s->op_addr, s->op_size);
    }
    if (s->op != OP_NONE && !cut) {
        s->sr |= SR_EOP;
    }
    s->op = OP_NONE;
    s->sr &= ~SR_BSY;
    s->cr &= ~CR_STRT;
    timer_del(s->timer);
    update_irq(s);
}

static void op_done(void *opaque)
{
    finish_op(opaque, false);
}

static void start_op(Stm32f4FlashState *s, int op, uint32_t addr, uint32_t len, int64_t ns)
{
    s->op = op;
    s->op_addr = addr;
    s->op_len = len;
    s->op_start = qemu_clock_get_ns(QEMU_CLOCK_VIRTUAL);
    s->op_end = s->op_start + ns;
    s->sr |= SR_BSY;
    timer_mod(s->timer, s->op_end);
    qemu_irq_pulse(s->op_out);
}

/* Typical erase time (DS8626): by sector size, at x8 or at x16 and wider. */
static int64_t erase_ns(Stm32f4FlashState *s, uint32_t bytes)
{
    const unsigned psize = (s->cr >> CR_PSIZE_SHIFT) & 3;
    const int64_t ms = bytes <= 0x4000 ? (psize == 0 ? 400 : psize == 1 ? 300 : 250)
                     : bytes <= 0x10000 ? (psize == 0 ? 1200 : psize == 1 ? 700 : 550)
                     : (psize == 0 ? 2000 : psize == 1 ? 1300 : 1000);
    return ms * 1000000;
}

static void start_erase(Stm32f4FlashState *s)
{
    if (s->cr & CR_MER) {
        int64_t ns = 0;
        for (int i = 0; i < NUM_SECTORS; ++i) {
            ns += erase_ns(s, sector_base[i + 1] - sector_base[i]);
        }
        start_op(s, OP_ERASE, 0, FLASH_BYTES, ns);
    } else if (s->cr & CR_SER) {
        const unsigned snb = (s->cr >> CR_SNB_SHIFT) & 0xF;
        if (snb >= NUM_SECTORS) {
            s->sr |= SR_PGSERR;
            qemu_log_mask(LOG_GUEST_ERROR, "stm32f4-flash: erase of sector %u: no such sector\n", snb);
            return;
        }
        const uint32_t len = sector_base[snb + 1] - sector_base[snb];
        start_op(s, OP_ERASE, sector_base[snb], len, erase_ns(s, len));
    } else {
        s->sr |= SR_PGSERR;
    }
}

static void check_latency(Stm32f4FlashState *s)
{
    const uint64_t hz = clock_get_hz(s->hclk);
    const unsigned ws = s->acr & 7;
    if (hz > (uint64_t)(ws + 1) * 30000000u) {
        qemu_log_mask(LOG_GUEST_ERROR,
                      "stm32f4-flash: %u wait states at HCLK %" PRIu64 " Hz: the part needs %u\n",
                      ws, hz, (unsigned)((hz - 1) / 30000000u));
    }
}

static void hclk_changed(void *opaque, ClockEvent event)
{
    check_latency(opaque);
}

static uint64_t flash_reg_read(void *opaque, hwaddr addr, unsigned size)
{
    Stm32f4FlashState *s = opaque;
    switch (addr) {
    case R_ACR:
        return s->acr;
    case R_SR:
        return s->sr;
    case R_CR:
        return s->cr;
    case R_OPTCR:
        return 0x0FFFAAED;
    }
    return 0;
}

static MemTxResult flash_reg_write(void *opaque, hwaddr addr, uint64_t val, unsigned size,
                                   MemTxAttrs attrs)
{
    Stm32f4FlashState *s = opaque;
    const uint32_t v = val;

    switch (addr) {
    case R_ACR:
        s->acr = v & 0x1F07;
        check_latency(s);
        break;
    case R_KEYR:
        if (!s->locked_hard && (s->cr & CR_LOCK) && s->key_state == 0 && v == KEY1) {
            s->key_state = 1;
        } else if (!s->locked_hard && (s->cr & CR_LOCK) && s->key_state == 1 && v == KEY2) {
            s->key_state = 0;
            s->cr &= ~CR_LOCK;
        } else {
            qemu_log_mask(LOG_GUEST_ERROR, "stm32f4-flash: KEYR 0x%08x out of sequence: "
                          "bus error, CR locked until reset\n", v);
            s->locked_hard = true;
            s->key_state = 0;
            s->cr |= CR_LOCK;
            return MEMTX_ERROR;
        }
        break;
    case R_OPTKEYR:
    case R_OPTCR:
        qemu_log_mask(LOG_UNIMP, "stm32f4-flash: option bytes not modelled\n");
        break;
    case R_SR:
        s->sr &= ~(v & (SR_ERRORS | SR_EOP));
        update_irq(s);
        break;
    case R_CR:
        if (s->sr & SR_BSY) {
            finish_op(s, false); /* the write waits for the operation to end */
        }
        if (s->cr & CR_LOCK) {
            break; /* locked: nothing changes (LOCK stays set) */
        }
        s->cr = (v & (CR_WRITABLE | CR_LOCK));
        if (v & CR_STRT) {
            start_erase(s);
            if (s->sr & SR_BSY) {
                s->cr |= CR_STRT; /* until BSY clears */
            }
        }
        update_irq(s);
        break;
    default:
        qemu_log_mask(LOG_GUEST_ERROR, "stm32f4-flash: write to 0x%" HWADDR_PRIx "\n", addr);
    }
    return MEMTX_OK;
}

static MemTxResult flash_reg_read_attrs(void *opaque, hwaddr addr, uint64_t *data,
                                        unsigned size, MemTxAttrs attrs)
{
    *data = flash_reg_read(opaque, addr, size);
    return MEMTX_OK;
}

static const MemoryRegionOps flash_reg_ops = {
    .read_with_attrs = flash_reg_read_attrs,
    .write_with_attrs = flash_reg_write,
    .endianness = DEVICE_LITTLE_ENDIAN,
    .valid = { .min_access_size = 4, .max_access_size = 4 },
};

/* A store into the array (reads never get here: the array is read as memory). */
static void flash_array_write(void *opaque, hwaddr addr, uint64_t val, unsigned size)
{
    Stm32f4FlashState *s = opaque;
    const unsigned psize = 1u << ((s->cr >> CR_PSIZE_SHIFT) & 3);

    if (s->sr & SR_BSY) {
        finish_op(s, false); /* the store waits for the operation to end */
    }
    if (!(s->cr & CR_PG) || (s->cr & CR_LOCK)) {
        s->sr |= SR_PGSERR;
    } else if (size != psize) {
        s->sr |= SR_PGPERR;
    } else if (addr % size) {
        s->sr |= SR_PGAERR;
    } else {
        start_op(s, OP_PROGRAM, addr, size, PROGRAM_NS);
        s->op_data = val;
        s->op_size = size;
        return;
    }
    qemu_log_mask(LOG_GUEST_ERROR, "stm32f4-flash: store of %u bytes at 0x%08" HWADDR_PRIx
                  " refused (SR 0x%08x, CR 0x%08x)\n", size, addr + 0x08000000, s->sr, s->cr);
}

static uint64_t flash_array_read(void *opaque, hwaddr addr, unsigned size)
{
    Stm32f4FlashState *s = opaque;
    uint64_t v = 0;
    memcpy(&v, s->mem + addr, size);
    return le64_to_cpu(v);
}

static const MemoryRegionOps flash_array_ops = {
    .read = flash_array_read,
    .write = flash_array_write,
    .endianness = DEVICE_LITTLE_ENDIAN,
    .valid = { .min_access_size = 1, .max_access_size = 4 },
};

static void flash_reset(DeviceState *dev)
{
    Stm32f4FlashState *s = STM32F4_FLASH(dev);
    if (s->op != OP_NONE) {
        finish_op(s, true);
    }
    s->acr = 0;
    s->sr = 0;
    s->cr = CR_LOCK;
    s->key_state = 0;
    s->locked_hard = false;
    update_irq(s);
}

static void open_backing(Stm32f4FlashState *s, Error **errp)
{
    s->fd = open(s->file, O_RDWR | O_CREAT, 0644);
    if (s->fd < 0) {
        error_setg_errno(errp, errno, "stm32f4-flash: cannot open %s", s->file);
        return;
    }
    const ssize_t got = pread(s->fd, s->mem, FLASH_BYTES, 0);
    if (got < 0) {
        error_setg_errno(errp, errno, "stm32f4-flash: cannot read %s", s->file);
        return;
    }
    if (got < FLASH_BYTES) {
        /* A new (or short) file: the rest is erased flash. */
        memset(s->mem + got, 0xFF, FLASH_BYTES - got);
        if (pwrite(s->fd, s->mem + got, FLASH_BYTES - got, got) != FLASH_BYTES - got) {
            error_setg_errno(errp, errno, "stm32f4-flash: cannot write %s", s->file);
        }
    }
}

static void flash_realize(DeviceState *dev, Error **errp)
{
    Stm32f4FlashState *s = STM32F4_FLASH(dev);
    Error *err = NULL;

    memory_region_init_rom_device(&s->array, OBJECT(dev), &flash_array_ops, s,
                                  "stm32f4-flash.array", FLASH_BYTES, &err);
    if (err) {
        error_propagate(errp, err);
        return;
    }
    sysbus_init_mmio(SYS_BUS_DEVICE(dev), &s->array);
    s->mem = memory_region_get_ram_ptr(&s->array);
    s->fd = -1;
    if (s->file && *s->file) {
        open_backing(s, errp);
    } else {
        memset(s->mem, 0xFF, FLASH_BYTES);
    }
    s->timer = timer_new_ns(QEMU_CLOCK_VIRTUAL, op_done, s);
}

static void flash_init(Object *obj)
{
    Stm32f4FlashState *s = STM32F4_FLASH(obj);
    memory_region_init_io(&s->iomem, obj, &flash_reg_ops, s, "stm32f4-flash", 0x400);
    sysbus_init_mmio(SYS_BUS_DEVICE(obj), &s->iomem);
    sysbus_init_irq(SYS_BUS_DEVICE(obj), &s->irq);
    qdev_init_gpio_out_named(DEVICE(obj), &s->op_out, FLASH_OUT_OP, 1);
    s->hclk = qdev_init_clock_in(DEVICE(obj), "hclk", hclk_changed, s, ClockUpdate);
}

static Property flash_properties[] = {
    DEFINE_PROP_STRING("file", Stm32f4FlashState, file),
    DEFINE_PROP_END_OF_LIST(),
};

static void flash_class_init(ObjectClass *klass, void *data)
{
    DeviceClass *dc = DEVICE_CLASS(klass);
    dc->realize = flash_realize;
    dc->reset = flash_reset;
    device_class_set_props(dc, flash_properties);
}

static const TypeInfo flash_info = {
    .name = TYPE_STM32F4_FLASH,
    .parent = TYPE_SYS_BUS_DEVICE,
    .instance_size = sizeof(Stm32f4FlashState),
    .instance_init = flash_init,
    .class_init = flash_class_init,
};

static void flash_register_types(void)
{
    type_register_static(&flash_info);
}

type_init(flash_register_types)
