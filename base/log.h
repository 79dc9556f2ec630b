/* One line per event to stderr, never per frame. In base/ (below platform/ and app/) so both log
 * the same way. */
#ifndef GK_LOG_H
#define GK_LOG_H

void gk_log(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
void gk_log_set_quiet(int quiet);

#endif
