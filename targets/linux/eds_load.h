/*
 * A device dictionary built at run time from an EDS or DCF (CiA 306): what
 * `canopen-device --eds FILE` runs. The file is read once; the loader makes
 * the same const structures the generator makes at build time (co_dev_t with
 * its entries, sub-entries, default image, limits and PDO table), in memory
 * it owns, so the core runs the device with its full CiA 301 behaviour.
 * Objects without behaviour in the core simply hold their values.
 *
 * What is taken from the file: every object of index 0x1000 and above (VAR,
 * DOMAIN, ARRAY, RECORD; CompactSubObj expanded), their data type (the CiA
 * 301 basic types), access type, PDO mapping, DefaultValue ($NODEID+n and
 * n+$NODEID on 8/16/32-bit values), LowLimit/HighLimit (integer types), and
 * in a DCF the ParameterValue (and [xxxxValue] of compact objects), which
 * overrides the default. PDOs are the pairs 0x1400+n/0x1600+n and
 * 0x1800+n/0x1A00+n numbered without gaps. Data type entries below 0x1000
 * are not objects of the device and are skipped.
 *
 * Storage: values of 0x1000..0x1FFF are communication parameters, others
 * application values, 0x1001/0x1003/0x1010/0x1011 are not stored (as the
 * generator does). String capacities: the default's length, at least 32
 * bytes when the value is writable.
 */
#ifndef EDS_LOAD_H
#define EDS_LOAD_H

#include <stddef.h>

#include "co/co_node.h"

typedef struct eds_dev eds_dev_t;

/** Load @p path. NULL on failure with one line (no newline) in @p err:
 *  "FILE:LINE: [SECTION] KEY: problem" (or "FILE: problem" when no line
 *  applies). */
eds_dev_t *eds_load_file(const char *path, char *err, size_t errcap);

/** Load from @p text (NUL-terminated; @p name is used in messages and as the
 *  device's name). */
eds_dev_t *eds_load_text(const char *name, const char *text, char *err, size_t errcap);

/** The dictionary (valid until eds_free). */
const co_dev_t *eds_device(const eds_dev_t *d);

/** The file's text, NUL-terminated (for --export-eds). */
const char *eds_text(const eds_dev_t *d);

/** Warnings, one per line ('\n'-terminated; "" for none): objects left out
 *  (a data type that is not a CiA 301 basic type) and values taken as they
 *  are (a DOMAIN default that is not hex). */
const char *eds_warnings(const eds_dev_t *d);

/** A one-line summary: product name and counts of objects and PDOs. */
const char *eds_summary(const eds_dev_t *d);

/** The device's name: the name of the file it was loaded from. */
const char *eds_name(const eds_dev_t *d);

void eds_free(eds_dev_t *d);

#endif /* EDS_LOAD_H */
