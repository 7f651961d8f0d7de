/* The bootloader's logic on the host (boot/): CRC, image header, layout, request, boot decision and
 * the update's commands, each refusal named and nothing written by a refused command.
 *
 * Expectations come from outside the code under test: CRC-32 check values (0xCBF43926 for
 * "123456789", 0x352441C2 for "abc"), the image built by the fixture with a bitwise CRC, the
 * F405's sector table of RM0090 worked by hand, the flash compared word for word before and after. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "boot/crc32.h"
#include "boot/decide.h"
#include "boot/image.h"
#include "boot/layout.h"
#include "boot/request.h"
#include "boot/update.h"
#include "boot_fixture.h"

static sim_flash flash, snapshot;
static flash_ops ops;
static boot_layout layout;
static boot_update up;
static uint8_t img[FX_IMAGE_MAX + BOOT_BLOCK_BYTES];
static uint32_t BOARD;

#define LEN 87040u /* 85 KiB: the application's size today, sectors 1..4 */

static void fresh(void)
{
    fx_flash_init(&flash, 7);
    ops = sim_flash_ops(&flash);
    assert_int_equal(boot_layout_stm32f4(&layout, 1, 6), 0);
    BOARD = fx_crc32((const uint8_t *)FX_BOARD_NAME, (uint32_t)strlen(FX_BOARD_NAME));
    boot_update_init(&up, &layout, &ops, BOARD);
    fx_image(img, LEN, BOARD, 0x020000u, 42);
}

static boot_choice decide(boot_image_status *why)
{
    boot_image_header h;
    return boot_decide(&layout, (const uint8_t *)flash.words, BOARD, false, why, &h);
}

static void same_flash(void)
{
    assert_memory_equal(flash.words, snapshot.words, sizeof flash.words);
    assert_int_equal(flash.programs, snapshot.programs);
    assert_memory_equal(flash.erases, snapshot.erases, sizeof flash.erases);
}

static void test_crc32_check_values(void **state)
{
    (void)state;
    assert_int_equal(crc32_update(0, "123456789", 9), 0xCBF43926u);
    assert_int_equal(crc32_update(crc32_update(0, "1234", 4), "56789", 5), 0xCBF43926u);
    assert_int_equal(crc32_update(0, "", 0), 0);
    assert_int_equal(boot_board_id("abc"), 0x352441C2u);
}

static void test_layout_of_the_f405(void **state)
{
    (void)state;
    boot_layout l;
    /* Bootloader in sector 0, application in 1..9, the parameter log in 10 and 11 after it. */
    assert_int_equal(boot_layout_stm32f4(&l, 1, 10), 0);
    assert_int_equal(l.flash_base, 0x08000000u);
    assert_int_equal(l.boot_bytes, 0x4000u);
    assert_int_equal(l.app_offset, 0x4000u);
    assert_int_equal(l.app_bytes, 3u * 16384u + 65536u + 5u * 131072u); /* 752 KiB */
    assert_int_equal(l.nsectors, 9);
    assert_int_equal(l.sectors[0].number, 1);
    assert_int_equal(l.sectors[3].number, 4);
    assert_int_equal(l.sectors[3].offset, 0x10000u);
    assert_int_equal(l.sectors[3].bytes, 0x10000u);
    assert_int_equal(l.sectors[4].offset, 0x20000u);
    assert_int_equal(l.sectors[8].offset, 0xA0000u);
    assert_int_equal(boot_layout_check(&l), 0);
    /* An image of 85 KiB needs sectors 1..4 (16 + 16 + 16 + 64 KiB); one byte past 48 KiB, four. */
    assert_int_equal(boot_layout_sectors_for(&l, 87040), 4);
    assert_int_equal(boot_layout_sectors_for(&l, 0xC000), 3);
    assert_int_equal(boot_layout_sectors_for(&l, 0xC004), 4);
    assert_int_equal(boot_layout_sectors_for(&l, 0), 0);
    assert_int_equal(boot_layout_sectors_for(&l, l.app_bytes), 9);
    assert_int_equal(boot_layout_sectors_for(&l, l.app_bytes + 4u), 0);
    /* Layouts that cannot be. */
    assert_int_equal(boot_layout_stm32f4(&l, 0, 10), -1);
    assert_int_equal(boot_layout_stm32f4(&l, 4, 4), -1);
    assert_int_equal(boot_layout_stm32f4(&l, 1, 13), -1);
    boot_layout bad;
    boot_layout_stm32f4(&bad, 1, 10);
    bad.app_offset = 0x2000; /* inside the bootloader */
    assert_int_equal(boot_layout_check(&bad), -1);
    boot_layout_stm32f4(&bad, 1, 10);
    bad.sectors[0].number = 0; /* the bootloader's own sector in the application area */
    assert_int_equal(boot_layout_check(&bad), -1);
    boot_layout_stm32f4(&bad, 1, 10);
    bad.sectors[2].offset += 4; /* a gap */
    assert_int_equal(boot_layout_check(&bad), -1);
    boot_layout_stm32f4(&bad, 1, 10);
    bad.app_bytes += 4;
    assert_int_equal(boot_layout_check(&bad), -1);
}

static void test_image_check(void **state)
{
    (void)state;
    fresh();
    boot_image_header h;
    const uint8_t *app = img;
    assert_int_equal(boot_image_check(app, FX_APP_BYTES, FX_APP_START, BOARD, &h), BOOT_IMAGE_OK);
    assert_int_equal(h.length, LEN);
    assert_int_equal(h.version, 0x020000u);
    assert_int_equal(boot_image_crc(app, LEN, 0), h.crc);
    /* Each part of the check, on a copy spoiled in one place. */
    static uint8_t bad[FX_IMAGE_MAX];
    memcpy(bad, img, LEN);
    bad[0x200] ^= 1; /* magic */
    assert_int_equal(boot_image_check(bad, FX_APP_BYTES, FX_APP_START, BOARD, &h), BOOT_IMAGE_NO_HEADER);
    memcpy(bad, img, LEN);
    bad[0x204] = 2; /* header version */
    assert_int_equal(boot_image_check(bad, FX_APP_BYTES, FX_APP_START, BOARD, &h), BOOT_IMAGE_UNKNOWN_HEADER);
    assert_int_equal(boot_image_check(img, FX_APP_BYTES, FX_APP_START, BOARD ^ 1u, &h), BOOT_IMAGE_BOARD);
    assert_int_equal(boot_image_check(img, LEN - 4u, FX_APP_START, BOARD, &h), BOOT_IMAGE_LENGTH);
    memcpy(bad, img, LEN);
    bad[LEN - 1] ^= 0x80; /* the last byte the CRC covers */
    assert_int_equal(boot_image_check(bad, FX_APP_BYTES, FX_APP_START, BOARD, &h), BOOT_IMAGE_CRC);
    memcpy(bad, img, LEN);
    bad[0x214] ^= 0x01; /* the crc word itself */
    assert_int_equal(boot_image_check(bad, FX_APP_BYTES, FX_APP_START, BOARD, &h), BOOT_IMAGE_CRC);
    /* Truncated: the end never written (erased) while the header says the whole length. */
    memcpy(bad, img, LEN);
    memset(bad + LEN - 1024u, 0xFF, 1024);
    assert_int_equal(boot_image_check(bad, FX_APP_BYTES, FX_APP_START, BOARD, &h), BOOT_IMAGE_CRC);
    /* A reset vector outside the image, its CRC made right: still not started. */
    fx_image(bad, LEN, BOARD, 1, 42);
    bad[4] = 0x01;
    bad[5] = bad[6] = 0;
    bad[7] = 0x08; /* 0x08000001: the bootloader's own sector */
    static uint8_t scratch[FX_IMAGE_MAX];
    memcpy(scratch, bad, 0x214);
    memcpy(scratch + 0x214, bad + 0x218, LEN - 0x218);
    const uint32_t c = fx_crc32(scratch, LEN - 4u);
    memcpy(bad + 0x214, &c, 4);
    assert_int_equal(boot_image_check(bad, FX_APP_BYTES, FX_APP_START, BOARD, &h), BOOT_IMAGE_VECTORS);
    assert_string_equal(boot_image_status_name(BOOT_IMAGE_CRC), "crc");
}

static void test_request_survives_a_reset_only(void **state)
{
    (void)state;
    boot_request r;
    uint8_t node = 99;
    uint32_t kbps = 12;
    memset(&r, 0xA5, sizeof r); /* what SRAM holds after a power cut: noise */
    assert_false(boot_request_take(&r, &node, &kbps));
    assert_int_equal(node, 99);
    assert_int_equal(kbps, 12);
    boot_request_set(&r, 7, 250);
    assert_true(boot_request_take(&r, &node, &kbps));
    assert_int_equal(node, 7);
    assert_int_equal(kbps, 250);
    assert_false(boot_request_take(&r, &node, &kbps)); /* taken once */
    boot_request_set(&r, 3, 500);
    r.node = 4; /* a bit flipped */
    assert_false(boot_request_take(&r, &node, &kbps));
    boot_request_set(&r, 3, 500);
    r.kbps = 1000; /* another */
    assert_false(boot_request_take(&r, &node, &kbps));
}

static void test_decision(void **state)
{
    (void)state;
    fresh();
    boot_image_status why;
    boot_image_header h;
    assert_int_equal(decide(&why), BOOT_STAY_NO_IMAGE); /* blank */
    assert_int_equal(why, BOOT_IMAGE_NO_HEADER);
    fx_flash_install(&flash, img, LEN);
    assert_int_equal(decide(&why), BOOT_START_APP);
    assert_int_equal(boot_decide(&layout, (const uint8_t *)flash.words, BOARD, true, &why, &h), BOOT_STAY_REQUEST);
    assert_int_equal(why, BOOT_IMAGE_OK);
    /* Another board's image, whole: never started. */
    assert_int_equal(boot_decide(&layout, (const uint8_t *)flash.words, BOARD + 1u, false, &why, &h),
                     BOOT_STAY_NO_IMAGE);
    assert_int_equal(why, BOOT_IMAGE_BOARD);
    /* Bit rot in the middle. */
    sim_flash_poke(&flash, FX_APP_OFFSET + 40000u, (uint8_t)~img[40000]);
    assert_int_equal(decide(&why), BOOT_STAY_NO_IMAGE);
    assert_int_equal(why, BOOT_IMAGE_CRC);
}

static void test_whole_update(void **state)
{
    (void)state;
    fresh();
    /* An old image in the area, and another's data after it (sector 5), which an 85 KiB update
     * must not touch. */
    static uint8_t old[FX_IMAGE_MAX + BOOT_BLOCK_BYTES];
    fx_image(old, 40000, BOARD, 0x010000u, 5);
    fx_flash_install(&flash, old, 40000);
    for (uint32_t i = 0; i < 16; ++i)
        flash.words[(0x20000u + 0x4000u * 0) / 4u + i] = 0x5EC70500u + i; /* sector 5 at 0x20000 */
    const fx_run r = fx_send(&up, img, LEN);
    assert_int_equal(r.erase, FW_REASON_NONE);
    assert_int_equal(r.first_block_refusal, FW_REASON_NONE);
    assert_int_equal(r.blocks_acked, 85);
    assert_int_equal(r.verify, FW_REASON_NONE);
    assert_memory_equal((const uint8_t *)flash.words + FX_APP_OFFSET, img, LEN);
    assert_true(fx_boot_intact(&flash));
    assert_int_equal(flash.erases[1] + flash.erases[2] + flash.erases[3] + flash.erases[4], 4);
    assert_int_equal(flash.erases[5], 0);
    for (uint32_t i = 0; i < 16; ++i)
        assert_int_equal(flash.words[0x20000u / 4u + i], 0x5EC70500u + i);
    assert_int_equal(flash.illegal, 0);
    boot_image_status why;
    assert_int_equal(decide(&why), BOOT_START_APP);
    /* Verified again: still good. */
    assert_int_equal(boot_update_verify(&up).reason, FW_REASON_NONE);
}

/* Until VERIFY, the header is not in flash: every block in, and still no image to start. */
static void test_header_held_back(void **state)
{
    (void)state;
    fresh();
    fx_flash_install(&flash, img, LEN); /* the same image, valid before */
    boot_image_status why;
    assert_int_equal(decide(&why), BOOT_START_APP);
    assert_int_equal(boot_update_erase(&up, LEN).reason, FW_REASON_NONE);
    const uint32_t blocks = (LEN + BOOT_BLOCK_BYTES - 1u) / BOOT_BLOCK_BYTES;
    for (uint32_t b = 0; b < blocks; ++b) {
        bool answered;
        const uint32_t bytes = LEN - b * 1024u < 1024u ? LEN - b * 1024u : 1024u;
        assert_int_equal(fx_block(&up, img, b, (bytes + 7u) / 8u, fx_crc32(img + b * 1024u, bytes), &answered).reason,
                         FW_REASON_NONE);
        assert_true(answered);
    }
    for (uint32_t i = 0; i < 48u; ++i)
        assert_int_equal(((const uint8_t *)flash.words)[FX_APP_OFFSET + 0x200u + i], 0xFF);
    assert_int_equal(decide(&why), BOOT_STAY_NO_IMAGE);
    assert_int_equal(why, BOOT_IMAGE_NO_HEADER);
    assert_int_equal(boot_update_verify(&up).reason, FW_REASON_NONE);
    assert_int_equal(decide(&why), BOOT_START_APP);
}

static void erase_ok(void)
{
    assert_int_equal(boot_update_erase(&up, LEN).reason, FW_REASON_NONE);
}

static void block_ok(uint32_t b)
{
    bool answered;
    assert_int_equal(fx_block(&up, img, b, 128, fx_crc32(img + b * 1024u, 1024), &answered).reason, FW_REASON_NONE);
    assert_true(answered);
}

static void test_refusals_write_nothing(void **state)
{
    (void)state;
    fresh();
    bool answered;
    /* Before ERASE: state. */
    snapshot = flash;
    assert_int_equal(fx_block(&up, img, 0, 128, fx_crc32(img, 1024), &answered).reason, FW_REASON_STATE);
    same_flash();
    /* Lengths that cannot be: nothing erased. */
    assert_int_equal(boot_update_erase(&up, 0).reason, FW_REASON_LENGTH);
    assert_int_equal(boot_update_erase(&up, LEN + 2u).reason, FW_REASON_LENGTH);
    assert_int_equal(boot_update_erase(&up, FX_APP_BYTES + 4u).reason, FW_REASON_LENGTH);
    assert_int_equal(boot_update_erase(&up, 0x100).reason, FW_REASON_LENGTH); /* shorter than a header */
    same_flash();
    erase_ok();
    block_ok(0);
    block_ok(1);
    snapshot = flash;
    /* Out of order: block 3 where 2 is due; names the one expected. */
    boot_verdict v = fx_block(&up, img, 3, 128, fx_crc32(img + 3u * 1024u, 1024), &answered);
    assert_int_equal(v.reason, FW_REASON_ORDER);
    assert_int_equal(v.where, 2);
    assert_int_equal(v.field, 2);
    v = fx_block(&up, img, 1, 128, fx_crc32(img + 1024u, 1024), &answered); /* again */
    assert_int_equal(v.reason, FW_REASON_ORDER);
    /* Beyond the length (85 blocks: 0..84). */
    v = fx_block(&up, img, 85, 128, 0, &answered);
    assert_int_equal(v.reason, FW_REASON_ADDRESS);
    assert_int_equal(v.where, 85);
    /* Frames other than the block's. */
    v = fx_block(&up, img, 2, 127, fx_crc32(img + 2048u, 1024), &answered);
    assert_int_equal(v.reason, FW_REASON_LENGTH);
    assert_int_equal(v.where, 128);
    /* A CRC that does not match its frames. */
    v = fx_block(&up, img, 2, 128, fx_crc32(img + 2048u, 1024) ^ 4u, &answered);
    assert_true(answered);
    assert_int_equal(v.reason, FW_REASON_CRC);
    assert_int_equal(v.where, 2);
    /* VERIFY with blocks missing. */
    v = boot_update_verify(&up);
    assert_int_equal(v.reason, FW_REASON_LENGTH);
    assert_int_equal(v.where, 2);
    same_flash();
    /* And the update goes on from block 2. */
    for (uint32_t b = 2; b < 85; ++b)
        block_ok(b);
    assert_int_equal(boot_update_verify(&up).reason, FW_REASON_NONE);
}

/* Frames lost: the next WRITE finds the block open; it is refused (length) and nothing of it was
 * written; the new WRITE is not the next block, refused order. */
static void test_lost_frames(void **state)
{
    (void)state;
    fresh();
    erase_ok();
    block_ok(0);
    snapshot = flash;
    boot_verdict v, dropped;
    uint8_t dropped_seq = 0, seq;
    (void)boot_update_write(&up, 41, 1, 128, fx_crc32(img + 1024u, 1024), &v, &dropped, &dropped_seq);
    assert_int_equal(v.reason, FW_REASON_NONE);
    for (uint32_t k = 0; k < 100; ++k)
        assert_int_equal(boot_update_data(&up, img + 1024u + 8u * k, &v, &seq), 0);
    assert_int_equal(boot_update_write(&up, 42, 2, 128, fx_crc32(img + 2048u, 1024), &v, &dropped, &dropped_seq), 1);
    assert_int_equal(dropped.reason, FW_REASON_LENGTH);
    assert_int_equal(dropped_seq, 41);
    assert_int_equal(v.reason, FW_REASON_ORDER);
    assert_int_equal(v.where, 1);
    /* The rest of the refused block's frames are dropped. */
    assert_int_equal(boot_update_data(&up, img, &v, &seq), 0);
    same_flash();
    block_ok(1);
}

static void test_foreign_and_bad_headers(void **state)
{
    (void)state;
    fresh();
    static uint8_t other[FX_IMAGE_MAX + BOOT_BLOCK_BYTES];
    bool answered;
    /* Built for another board. */
    fx_image(other, LEN, BOARD ^ 0x100u, 0x020000u, 42);
    erase_ok();
    snapshot = flash;
    boot_verdict v = fx_block(&up, other, 0, 128, fx_crc32(other, 1024), &answered);
    assert_int_equal(v.reason, FW_REASON_BOARD);
    same_flash();
    /* Its header says another length than was erased for. */
    fx_image(other, LEN - 1024u, BOARD, 0x020000u, 42);
    v = fx_block(&up, other, 0, 128, fx_crc32(other, 1024), &answered);
    assert_int_equal(v.reason, FW_REASON_HEADER);
    assert_int_equal(v.field, 1);
    /* No header at all. */
    memcpy(other, img, 1024);
    other[0x203] = 0;
    v = fx_block(&up, other, 0, 128, fx_crc32(other, 1024), &answered);
    assert_int_equal(v.reason, FW_REASON_HEADER);
    assert_int_equal(v.field, 0);
    same_flash();
    /* An image whose header's CRC is wrong: every block taken, VERIFY refuses, nothing bootable. */
    memcpy(other, img, LEN);
    other[LEN - 8u] ^= 0x10; /* the blocks' own CRCs are the host's, of these bytes */
    const fx_run r = fx_send(&up, other, LEN);
    assert_int_equal(r.first_block_refusal, FW_REASON_NONE);
    assert_int_equal(r.verify, FW_REASON_CRC);
    boot_image_status why;
    assert_int_equal(decide(&why), BOOT_STAY_NO_IMAGE);
    assert_int_equal(why, BOOT_IMAGE_NO_HEADER);
    /* ... and the update must start again from ERASE. */
    assert_int_equal(boot_update_verify(&up).reason, FW_REASON_STATE);
    assert_int_equal(fx_send(&up, img, LEN).verify, FW_REASON_NONE);
    assert_int_equal(decide(&why), BOOT_START_APP);
    assert_true(fx_boot_intact(&flash));
}

/* An image whose length is not a whole block: its last block short, its last frame half used. */
static void test_short_last_block(void **state)
{
    (void)state;
    fresh();
    const uint32_t len = 5u * 1024u + 12u;
    fx_image(img, len, BOARD, 3, 9);
    const fx_run r = fx_send(&up, img, len);
    assert_int_equal(r.blocks_acked, 6);
    assert_int_equal(r.verify, FW_REASON_NONE);
    boot_image_status why;
    assert_int_equal(decide(&why), BOOT_START_APP);
    /* Past the image: erased, untouched. */
    assert_int_equal(flash.words[(FX_APP_OFFSET + len) / 4u], 0xFFFFFFFFu);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_crc32_check_values),
        cmocka_unit_test(test_layout_of_the_f405),
        cmocka_unit_test(test_image_check),
        cmocka_unit_test(test_request_survives_a_reset_only),
        cmocka_unit_test(test_decision),
        cmocka_unit_test(test_whole_update),
        cmocka_unit_test(test_header_held_back),
        cmocka_unit_test(test_refusals_write_nothing),
        cmocka_unit_test(test_lost_frames),
        cmocka_unit_test(test_foreign_and_bad_headers),
        cmocka_unit_test(test_short_last_block),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
