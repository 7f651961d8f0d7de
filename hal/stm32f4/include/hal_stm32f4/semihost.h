/* Semihosting output for the test and benchmark images that run under QEMU
 * (-semihosting-config enable=on,target=native).  Never linked into the production image: with
 * no debugger attached, a semihosting call on real hardware stops the core. */
#ifndef TSE_BOARD_SEMIHOST_H
#define TSE_BOARD_SEMIHOST_H

void sh_puts(const char *s);          /* writes s as it is */
void sh_printf(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
__attribute__((noreturn)) void sh_exit(int status); /* QEMU exits with 0 for 0, 1 otherwise */

#endif
