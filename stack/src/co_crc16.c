#include "co_crc16.h"

uint16_t co_crc16(uint16_t crc, const uint8_t *data, uint32_t len)
{
    /* CRC-16/CCITT (polynomial 0x1021) a byte at a time without a table:
     * x^16 = x^12 + x^5 + 1 folds the byte's eight polynomial steps into
     * x ^= x >> 4 and three shifted copies of x. */
    for (uint32_t i = 0U; i < len; i++) {
        uint8_t x = (uint8_t)((crc >> 8U) ^ data[i]);
        x ^= (uint8_t)(x >> 4U);
        crc = (uint16_t)((uint16_t)(crc << 8U) ^ (uint16_t)((uint16_t)x << 12U) ^
                         (uint16_t)((uint16_t)x << 5U) ^ x);
    }
    return crc;
}
