/* Issue 28, "never a bricked board": the power goes at every flash operation of an update in turn
 * (each sector erase and each word program is one, as in the parameter log's cut test), then
 * the board starts again: SRAM is noise after a power cut, so no update request survives it, and
 * the bootloader decides (boot/decide.h) from the flash alone.
 *
 * After every cut: the start comes up in the bootloader, or in a whole application, the old one
 * or the new one, byte for byte; never in a corrupt, truncated or foreign image, never in neither
 * (the bootloader's sector is whole: never erased, never written); and the same update, sent again
 * from its ERASE, completes and starts the new application.
 *
 * The images are built by the fixture (bitwise CRC); which image started is judged by comparing
 * the area with the images the test made, not by what the bootloader reports. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "boot/decide.h"
#include "boot/layout.h"
#include "boot/update.h"
#include "boot_fixture.h"

static sim_flash flash, before;
static flash_ops ops;
static boot_layout layout;
static boot_update up;
static uint8_t old_img[FX_IMAGE_MAX + BOOT_BLOCK_BYTES], new_img[FX_IMAGE_MAX + BOOT_BLOCK_BYTES];
static uint32_t BOARD;

typedef struct {
    unsigned cuts, in_erase, boot_bootloader, boot_new, boot_old, redone;
} tally;

enum { CAME_BOOTLOADER, CAME_NEW, CAME_OLD };

/* Which start the flash gives, judged against the images themselves. */
static int start(uint32_t old_len, uint32_t new_len)
{
    boot_image_status why;
    boot_image_header h;
    const boot_choice c = boot_decide(&layout, (const uint8_t *)flash.words, BOARD, false, &why, &h);
    assert_true(fx_boot_intact(&flash));
    if (c != BOOT_START_APP)
        return CAME_BOOTLOADER;
    const uint8_t *app = (const uint8_t *)flash.words + FX_APP_OFFSET;
    if (h.length == new_len && memcmp(app, new_img, new_len) == 0)
        return CAME_NEW;
    if (h.length == old_len && memcmp(app, old_img, old_len) == 0)
        return CAME_OLD;
    fail_msg("the bootloader would start an image that is neither the old nor the new one (length %u)",
             (unsigned)h.length);
    return -1;
}

static void setup(uint32_t old_len, uint32_t new_len)
{
    assert_int_equal(boot_layout_stm32f4(&layout, 1, 6), 0);
    BOARD = fx_crc32((const uint8_t *)FX_BOARD_NAME, (uint32_t)strlen(FX_BOARD_NAME));
    fx_image(old_img, old_len, BOARD, 0x010000u, 11);
    fx_image(new_img, new_len, BOARD, 0x020000u, 22);
    fx_flash_init(&before, 5);
    fx_flash_install(&before, old_img, old_len);
}

/* One cut at operation k (1: the first) with torn-state seed `seed`; the tally counts it.
 * Returns where the start came up. */
static int cut_once(uint64_t k, uint32_t seed, uint32_t old_len, uint32_t new_len, tally *t)
{
    flash = before;
    flash.rng = seed * 2654435761u + 1u;
    ops = sim_flash_ops(&flash);
    boot_update_init(&up, &layout, &ops, BOARD);
    sim_flash_cut_after(&flash, k);
    const fx_run r = fx_send(&up, new_img, new_len);
    assert_true(flash.cut_happened);
    assert_true(r.erase != FW_REASON_NONE || r.first_block_refusal != FW_REASON_NONE || r.verify != FW_REASON_NONE);
    sim_flash_reboot(&flash);
    ++t->cuts;
    t->in_erase += flash.cut_in_erase;
    const int came = start(old_len, new_len);
    switch (came) {
    case CAME_BOOTLOADER: ++t->boot_bootloader; break;
    case CAME_NEW: ++t->boot_new; break;
    default: ++t->boot_old; break;
    }
    /* The bootloader takes the update again, from its ERASE. */
    boot_update_init(&up, &layout, &ops, BOARD);
    const fx_run again = fx_send(&up, new_img, new_len);
    assert_int_equal(again.verify, FW_REASON_NONE);
    assert_int_equal(start(old_len, new_len), CAME_NEW);
    ++t->redone;
    return came;
}

/* Operations of the same update uncut. */
static uint64_t ops_of_update(uint32_t new_len)
{
    flash = before;
    ops = sim_flash_ops(&flash);
    boot_update_init(&up, &layout, &ops, BOARD);
    const uint64_t from = flash.ops;
    assert_int_equal(fx_send(&up, new_img, new_len).verify, FW_REASON_NONE);
    assert_int_equal(flash.illegal, 0);
    return flash.ops - from;
}

static void report(const char *what, uint64_t n, const tally *t)
{
    print_message("%s: %llu flash operations, %u cuts (%u in an erase): started in the bootloader %u, "
                  "the new application %u, the old one %u, in neither 0; update sent again and completed %u\n",
                  what, (unsigned long long)n, t->cuts, t->in_erase, t->boot_bootloader, t->boot_new, t->boot_old,
                  t->redone);
}

/* Every cut point of a 24,676-byte update over a 30,000-byte application (sectors 1 and 2). */
static void test_cut_at_every_operation(void **state)
{
    (void)state;
    const uint32_t old_len = 30000u, new_len = 24676u;
    setup(old_len, new_len);
    const uint64_t n = ops_of_update(new_len);
    /* 2 erases and a program per word that is not 0xFFFFFFFF, the header's included (its last
     * word, reserved[1] = 0, too): counted from the image itself. */
    uint64_t words = 0;
    for (uint32_t i = 0; i < new_len; i += 4u) {
        uint32_t w;
        memcpy(&w, new_img + i, 4);
        words += w != 0xFFFFFFFFu;
    }
    assert_int_equal(n, 2u + words);
    tally t = {0};
    /* The new image starts only when the cut took the very last operation, the header's magic,
     * and the torn word happens to read the whole magic; the old one only while the first erase
     * left its sector as it was. */
    for (uint64_t k = 1; k <= n; ++k) {
        const int came = cut_once(k, (uint32_t)k, old_len, new_len, &t);
        assert_true(came != CAME_NEW || k == n);
        assert_true(came != CAME_OLD || k == 1);
    }
    /* The erases, where a cut leaves the most kinds of wreckage, and the magic, with more seeds. */
    for (uint32_t s = 1; s <= 32; ++s) {
        assert_true(cut_once(1, 1000u + s, old_len, new_len, &t) != CAME_NEW);
        assert_int_equal(cut_once(2, 2000u + s, old_len, new_len, &t), CAME_BOOTLOADER);
        assert_true(cut_once(n, 3000u + s, old_len, new_len, &t) != CAME_OLD);
    }
    report("power cut at every operation of a 24,676-byte update", n, &t);
    assert_int_equal(t.boot_bootloader + t.boot_new + t.boot_old, t.cuts);
    assert_true(t.boot_bootloader > 0);
}

/* The application's size today (85 KiB, sectors 1..4) over a 100,000-byte one (1..5): cut points
 * spread over the whole update, every erase among them. */
static void test_cut_a_whole_application(void **state)
{
    (void)state;
    const uint32_t old_len = 100000u, new_len = 87040u;
    setup(old_len, new_len);
    const uint64_t n = ops_of_update(new_len);
    tally t = {0};
    for (uint64_t k = 1; k <= 4; ++k)
        for (uint32_t s = 0; s < 8; ++s)
            cut_once(k, 77u * s + (uint32_t)k, old_len, new_len, &t);
    for (uint64_t k = 5; k <= n; k += 97u)
        cut_once(k, (uint32_t)k, old_len, new_len, &t);
    cut_once(n, 1, old_len, new_len, &t);
    cut_once(n - 1u, 1, old_len, new_len, &t);
    report("power cut at every 97th operation of an 87,040-byte update", n, &t);
    assert_int_equal(t.boot_bootloader + t.boot_new + t.boot_old, t.cuts);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_cut_at_every_operation),
        cmocka_unit_test(test_cut_a_whole_application),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
