/* One end of a byte channel to the emulated board (its CAN channel or its rig): a UNIX socket the
 * emulator serves (on the host), or a character device that leads to it (the VM's virtio port);
 * a terminal is put into raw mode. */
#ifndef EMU_LINK_ENDPOINT_H
#define EMU_LINK_ENDPOINT_H

#include <stddef.h>

/* Opens PATH for reading and writing.  Returns the descriptor, or -1 with errno set. */
int endpoint_open(const char *path);

/* Writes all n bytes (retrying short writes and interruptions).  Returns 0 or -1. */
int endpoint_write_all(int fd, const void *buf, size_t n);

#endif
