/*
 * Test helpers: frames written the way the manuals and our docs write them,
 * "601 40 00 10 00 00 00 00 00" (COB-ID in hex, then payload bytes), or
 * "701 R" / "701 R1" for a remote request (with an optional DLC).
 */
#ifndef TEST_FRAMES_H
#define TEST_FRAMES_H

#include <stddef.h>

#include "co/co_frame.h"

/** Parse @p text into a frame. Fails the running cmocka test on bad text. */
co_frame_t tf_parse(const char *text);

/** Format @p f as "581 43 00 10 00 92 01 02 00" into @p buf. */
void tf_format(const co_frame_t *f, char *buf, size_t cap);

/** Assert that @p f equals the frame written as @p expected, printing both. */
void tf_assert_frame(const co_frame_t *f, const char *expected,
                     const char *file, int line);
#define TF_ASSERT_FRAME(f, text) tf_assert_frame((f), (text), __FILE__, __LINE__)

#endif
