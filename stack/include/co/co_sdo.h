/**
 * @file co_sdo.h
 * Names for byte 0 of an SDO frame (CiA 301 7.2.4.3): the command
 * specifiers of client and server and the bits beside them. The server
 * (co_sdo_server.c) speaks in these; a test or a client may too.
 */
#ifndef CO_SDO_H
#define CO_SDO_H

#include <stdint.h>

/** The command specifier in byte 0 (bits 7..5). */
#define CO_SDO_CS(b0) ((uint8_t)((uint8_t)(b0) >> 5U))
/** Byte 0 holding command specifier @p cs, other bits 0. */
#define CO_SDO_B0(cs) ((uint8_t)((uint8_t)(cs) << 5U))

/* client command specifiers (ccs: client -> server) */
#define CO_SDO_CCS_DOWNLOAD_SEGMENT  0U
#define CO_SDO_CCS_DOWNLOAD_INITIATE 1U
#define CO_SDO_CCS_UPLOAD_INITIATE   2U
#define CO_SDO_CCS_UPLOAD_SEGMENT    3U
#define CO_SDO_CS_ABORT              4U /**< abort transfer, either direction */
#define CO_SDO_CCS_BLOCK_UPLOAD      5U
#define CO_SDO_CCS_BLOCK_DOWNLOAD    6U

/* server command specifiers (scs: server -> client) */
#define CO_SDO_SCS_UPLOAD_SEGMENT    0U
#define CO_SDO_SCS_DOWNLOAD_SEGMENT  1U
#define CO_SDO_SCS_UPLOAD_INITIATE   2U
#define CO_SDO_SCS_DOWNLOAD_INITIATE 3U
#define CO_SDO_SCS_BLOCK_DOWNLOAD    5U
#define CO_SDO_SCS_BLOCK_UPLOAD      6U

/* initiate (expedited / segmented) */
#define CO_SDO_SIZE_IND  0x01U /**< s: the size is indicated */
#define CO_SDO_EXPEDITED 0x02U /**< e: expedited, the data in bytes 4..7 */
#define CO_SDO_N_SHIFT   2U    /**< n: bytes of 4 without data (bits 3..2, with e and s) */
/* segments */
#define CO_SDO_TOGGLE    0x10U /**< t: toggle bit */
#define CO_SDO_SEG_N_SHIFT 1U  /**< n: bytes of 7 without data (bits 3..1) */
#define CO_SDO_LAST_SEG  0x01U /**< c: no more segments */

/* block transfers: the subcommand in bits 1..0 (client and server) */
#define CO_SDO_BLK_INITIATE 0U
#define CO_SDO_BLK_END      1U
#define CO_SDO_BLK_ACK      2U /**< server (download) / client (upload): block acknowledged */
#define CO_SDO_BLK_START    3U /**< client: start the upload */
#define CO_SDO_BLK_SUB_MASK 0x03U
#define CO_SDO_BLK_CRC      0x04U /**< cc / sc: CRC supported */
#define CO_SDO_BLK_SIZE_IND 0x02U /**< s in a block initiate */
#define CO_SDO_BLK_N_SHIFT  2U    /**< n in a block end: bytes of 7 without data (bits 4..2) */
#define CO_SDO_BLK_LAST     0x80U /**< c in a block segment's sequence number byte */

#endif /* CO_SDO_H */
