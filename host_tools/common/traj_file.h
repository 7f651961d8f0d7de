/* A trajectory file, read whole and checked before anything is sent.
 *
 * The file is CSV, one row per trajectory point:  t,x,y,z,roll,pitch,yaw
 * with t in seconds, x, y, z in metres and roll, pitch, yaw in radians (R = Rz(yaw) Ry(pitch)
 * Rx(roll), docs/kinematics.md).  The rules, each refused with "PATH:LINE: what is wrong":
 *
 *  - Every row is exactly 7 numbers, comma-separated, spaces or tabs around them allowed, LF or
 *    CRLF line ends.  An empty field, text after a number, a non-number, or a row with more or
 *    fewer columns is an error that names the column, e.g.
 *        traj.csv:7: column 3 (y): not a number 'abc'
 *        traj.csv:9: 8 columns, expected 7 (t,x,y,z,roll,pitch,yaw)
 *  - A UTF-8 byte order mark at the start of the file is skipped.  Blank lines (spaces and tabs
 *    only) and lines whose first non-blank character is '#' are skipped.
 *  - The first other line may be a header: exactly the names t,x,y,z,roll,pitch,yaw, in any case,
 *    spaces around them allowed.  Any other first line that does not start with a number is an
 *    error naming the line.  A header anywhere else is a malformed row.
 *  - Every number is finite.  |x|, |y|, |z| <= 4 m and |roll|, |pitch|, |yaw| <= 3.141593 rad:
 *    the CAN wire carries 24-bit micrometres and microradians (+-4000000, +-3141593), e.g.
 *        traj.csv:12: column 2 (x) = 4.5 m is outside the wire's range -4..4 m
 *  - t is the time from the moment the controller starts the trajectory (once it holds traj_lead
 *    of it, its last row or a full queue: docs/protocol.md), when the plate is at rest
 *    where it is.  The wire carries the time from one row to the next in whole microseconds: each
 *    t is rounded to 1 us and each difference of rounded times (the first row's from 0) must be
 *    0.001 s to 60 s.  So the first row's t is 0.001 s to 60 s, and every later row's t exceeds
 *    the previous one's by 0.001 s to 60 s (differences rounded to 1 us).
 *  - At least 1 row and at most TRAJ_FILE_MAX_ROWS rows.  A line longer than LINE_READER_MAX
 *    bytes (4096) or holding a NUL byte is an error naming the line.
 *
 * A file that cannot be opened or read is "PATH: why".  Nothing is returned from a refused file. */
#ifndef TSE_HOST_TRAJ_FILE_H
#define TSE_HOST_TRAJ_FILE_H

#include <stddef.h>

#include "fw/proto_wire.h"

#define TRAJ_FILE_MAX_ROWS 1000000

/* The wire's ranges (see above), in SI. */
#define TRAJ_FILE_POS_MAX ((double)PROTO_POS_MAX_UM / PROTO_UM_PER_M)               /* m */
#define TRAJ_FILE_ANGLE_MAX ((double)PROTO_ANGLE_MAX_URAD / PROTO_URAD_PER_RAD)    /* rad */
#define TRAJ_FILE_DT_MIN_US ((long long)PROTO_DT_MIN_US)
#define TRAJ_FILE_DT_MAX_US ((long long)PROTO_DT_MAX_US)

typedef struct {
    double t;    /* [s] from the moment the controller starts the trajectory */
    double p[6]; /* x, y, z [m]; roll, pitch, yaw [rad] */
    int line;    /* 1-based line of the file the row came from */
} traj_row;

/* Reads path.  Returns the number of rows (>= 1) with *rows malloc'ed (caller frees), or -1
 * with a message "PATH:LINE: what is wrong" (or "PATH: ...") in err and *rows set to NULL. */
int traj_file_read(const char *path, traj_row **rows, char *err, size_t errlen);

/* The time of a row in whole microseconds, as the differences above are taken (t rounded to the
 * nearest microsecond, halves away from zero). */
long long traj_time_us(double t);

#endif
