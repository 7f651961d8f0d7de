/* The documentation strings of the firmware's tables (messages, fields, parameters): the host tools
 * print them (protogen's docs/protocol.md, DBC and Python tables, tsectl's params list); the board
 * image is built with TSE_FW_DOCS 0 and carries none of that text, which flash is too scarce for
 * (the build prints the image's size). */
#ifndef FW_DOC_H
#define FW_DOC_H

#ifndef TSE_FW_DOCS
#define TSE_FW_DOCS 1
#endif

#if TSE_FW_DOCS
#define FW_DOC(text) text
#else
#define FW_DOC(text) ""
#endif

#endif
