/* A waypoint file: the poses a planned path passes through (tse-kin plan, tsectl path), read
 * whole and checked before anything is planned.
 *
 * CSV as a trajectory file (traj_file.h): comma-separated fields, spaces or tabs around them, LF or
 * CRLF, a UTF-8 BOM skipped, blank lines and '#' comment lines skipped.  Without a header a row is
 * x,y,z,roll,pitch,yaw (metres, radians).  A header (the first other line, when it does not start
 * with a number) names the columns in any order, without regard to case: x, y, z, roll, pitch, yaw,
 * each exactly once, and optionally
 *   t  the time the plate passes the waypoint [s] from the start (the first waypoint's is 0);
 *      empty where free; given times increase;
 *   v  the plate's speed from this waypoint to the next at most [m/s], > 0; empty where none.
 * Pose values are finite and within the wire's ranges (|x|, |y|, |z| <= 4 m, angles within
 * +-3.141593 rad).  Each refusal is "PATH:LINE: what is wrong", naming the column; a file that
 * cannot be read is "PATH: why".  At least 2 and at most WAYPOINT_FILE_MAX_ROWS rows.  Nothing
 * is returned from a refused file. */
#ifndef TSE_HOST_WAYPOINT_FILE_H
#define TSE_HOST_WAYPOINT_FILE_H

#include <stddef.h>

#define WAYPOINT_FILE_MAX_ROWS 100000

typedef struct {
    double pose[6]; /* x, y, z [m], roll, pitch, yaw [rad] */
    double t;       /* [s], NAN where free */
    double v;       /* [m/s], NAN where none */
    int line;
} waypoint_row;

/* Reads path.  Returns the number of rows with *rows malloc'ed (caller frees), or -1 with the
 * message in err and *rows NULL. */
int waypoint_file_read(const char *path, waypoint_row **rows, char *err, size_t errlen);

#endif
