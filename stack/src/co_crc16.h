/* CRC-16 of SDO block transfer: CCITT polynomial 0x1021, initial value 0,
 * no reflection (CiA 301, 7.2.4.3.16). */
#ifndef CO_CRC16_H
#define CO_CRC16_H

#include <stdint.h>

uint16_t co_crc16(uint16_t crc, const uint8_t *data, uint32_t len);

#endif
