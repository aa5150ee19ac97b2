// Inflates a raw DEFLATE stream (RFC 1951), as zlib's deflate writes it, synchronously. The
// inspector embeds its input compressed, so that the browser reads a tenth of the bytes. (The
// browser's DecompressionStream is asynchronous: the page would be drawn after its load event,
// when headless tools such as --dump-dom and --screenshot have already taken it; and in
// Chromium 156 it took longer for the 10,000-pass plan than this function.)
// loomInflate(bytes, size) returns a Uint8Array of `size` bytes, and throws on a stream that
// is malformed or does not hold exactly `size` bytes.
"use strict";

const loomInflate = (function () {
  const LENGTH_BASE = [3, 4, 5, 6, 7, 8, 9, 10, 11, 13, 15, 17, 19, 23, 27, 31, 35, 43, 51, 59, 67, 83, 99, 115, 131, 163, 195, 227, 258];
  const LENGTH_EXTRA = [0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2, 2, 3, 3, 3, 3, 4, 4, 4, 4, 5, 5, 5, 5, 0];
  const DISTANCE_BASE = [1, 2, 3, 4, 5, 7, 9, 13, 17, 25, 33, 49, 65, 97, 129, 193, 257, 385, 513, 769, 1025, 1537, 2049, 3073,
    4097, 6145, 8193, 12289, 16385, 24577];
  const DISTANCE_EXTRA = [0, 0, 0, 0, 1, 1, 2, 2, 3, 3, 4, 4, 5, 5, 6, 6, 7, 7, 8, 8, 9, 9, 10, 10, 11, 11, 12, 12, 13, 13];
  // The order in which a dynamic block gives the code lengths of its code-length alphabet.
  const CODE_LENGTH_ORDER = [16, 17, 18, 0, 8, 7, 9, 6, 10, 5, 11, 4, 12, 3, 13, 2, 14, 1, 15];

  // A canonical Huffman code as one table indexed by the next `bits` bits of the stream (the
  // first bit lowest, as DEFLATE packs codes): each entry is symbol << 4 | code length, or 0
  // where no code begins with those bits.
  function Code() {
    this.table = new Uint16Array(1 << 15);
    this.bits = 0;
  }
  Code.prototype.build = function (lengths, first, count) {
    const perLength = new Uint16Array(16);
    for (let i = 0; i < count; ++i) perLength[lengths[first + i]]++;
    perLength[0] = 0;
    let bits = 15;
    while (bits > 0 && perLength[bits] === 0) --bits;
    const next = new Uint16Array(16);
    for (let length = 1, code = 0; length <= 15; ++length) {
      code = (code + perLength[length - 1]) << 1;
      next[length] = code;
      if (code + perLength[length] > 1 << length) throw new Error("inflate: oversubscribed Huffman code");
    }
    const size = 1 << bits;
    this.table.fill(0, 0, size);
    for (let symbol = 0; symbol < count; ++symbol) {
      const length = lengths[first + symbol];
      if (length === 0) continue;
      let code = next[length]++;
      let reversed = 0;
      for (let i = 0; i < length; ++i) {
        reversed = (reversed << 1) | (code & 1);
        code >>= 1;
      }
      for (let at = reversed; at < size; at += 1 << length) this.table[at] = (symbol << 4) | length;
    }
    this.bits = bits;
  };

  // The input with the bits read ahead of it: `buffer` holds `count` bits, the next one lowest.
  function Bits(input) {
    this.input = input;
    this.pos = 0;
    this.buffer = 0;
    this.count = 0;
  }
  Bits.prototype.take = function (n) {
    while (this.count < n) {
      this.buffer |= (this.input[this.pos++] | 0) << this.count;
      this.count += 8;
    }
    const value = this.buffer & ((1 << n) - 1);
    this.buffer >>>= n;
    this.count -= n;
    return value;
  };
  Bits.prototype.decode = function (code) {
    while (this.count < code.bits) {
      this.buffer |= (this.input[this.pos++] | 0) << this.count;
      this.count += 8;
    }
    const entry = code.table[this.buffer & ((1 << code.bits) - 1)];
    const length = entry & 15;
    if (length === 0) throw new Error("inflate: invalid Huffman code");
    this.buffer >>>= length;
    this.count -= length;
    return entry >> 4;
  };

  const literals = new Code();
  const distances = new Code();
  const codeLengths = new Code();
  const lengths = new Uint8Array(286 + 30);

  function fixedCodes() {
    for (let i = 0; i < 288; ++i) lengths[i] = i < 144 ? 8 : i < 256 ? 9 : i < 280 ? 7 : 8;
    literals.build(lengths, 0, 288);
    lengths.fill(5, 0, 30);
    distances.build(lengths, 0, 30);
  }

  function dynamicCodes(bits) {
    const literalCount = bits.take(5) + 257;
    const distanceCount = bits.take(5) + 1;
    const lengthCount = bits.take(4) + 4;
    if (literalCount > 286 || distanceCount > 30) throw new Error("inflate: too many codes");
    lengths.fill(0, 0, 19);
    for (let i = 0; i < lengthCount; ++i) lengths[CODE_LENGTH_ORDER[i]] = bits.take(3);
    codeLengths.build(lengths, 0, 19);
    const total = literalCount + distanceCount;
    for (let i = 0; i < total;) {
      const symbol = bits.decode(codeLengths);
      if (symbol < 16) {
        lengths[i++] = symbol;
        continue;
      }
      let value = 0;
      let repeat;
      if (symbol === 16) {
        if (i === 0) throw new Error("inflate: repeat of no code length");
        value = lengths[i - 1];
        repeat = 3 + bits.take(2);
      } else {
        repeat = symbol === 17 ? 3 + bits.take(3) : 11 + bits.take(7);
      }
      if (i + repeat > total) throw new Error("inflate: code lengths overrun");
      lengths.fill(value, i, i + repeat);
      i += repeat;
    }
    if (lengths[256] === 0) throw new Error("inflate: no end-of-block code");
    literals.build(lengths, 0, literalCount);
    distances.build(lengths, literalCount, distanceCount);
  }

  // One block of Huffman codes into out from `at`; returns where it ended. The hot loop keeps
  // the bit reader in locals.
  function inflateCodes(bits, out, at) {
    const input = bits.input;
    const size = out.length;
    const literalTable = literals.table;
    const literalMask = (1 << literals.bits) - 1;
    const distanceTable = distances.table;
    const distanceMask = (1 << distances.bits) - 1;
    let pos = bits.pos;
    let buffer = bits.buffer;
    let count = bits.count;
    for (;;) {
      // 15 bits cover any code, 5 more the extra bits of a length.
      while (count < 20) {
        buffer |= (input[pos++] | 0) << count;
        count += 8;
      }
      let entry = literalTable[buffer & literalMask];
      let length = entry & 15;
      if (length === 0) throw new Error("inflate: invalid literal/length code");
      buffer >>>= length;
      count -= length;
      const symbol = entry >> 4;
      if (symbol < 256) {
        if (at >= size) throw new Error("inflate: more bytes than expected");
        out[at++] = symbol;
        continue;
      }
      if (symbol === 256) break;
      const lengthCode = symbol - 257;
      if (lengthCode >= 29) throw new Error("inflate: invalid length code");
      let extra = LENGTH_EXTRA[lengthCode];
      const matchLength = LENGTH_BASE[lengthCode] + (buffer & ((1 << extra) - 1));
      buffer >>>= extra;
      count -= extra;

      // The buffer takes at most 32 bits: the code first, then its extra bits.
      while (count < 15) {
        buffer |= (input[pos++] | 0) << count;
        count += 8;
      }
      entry = distanceTable[buffer & distanceMask];
      length = entry & 15;
      if (length === 0) throw new Error("inflate: invalid distance code");
      buffer >>>= length;
      count -= length;
      const distanceCode = entry >> 4;
      if (distanceCode >= 30) throw new Error("inflate: invalid distance code");
      extra = DISTANCE_EXTRA[distanceCode];
      while (count < extra) {
        buffer |= (input[pos++] | 0) << count;
        count += 8;
      }
      const distance = DISTANCE_BASE[distanceCode] + (buffer & ((1 << extra) - 1));
      buffer >>>= extra;
      count -= extra;
      if (distance > at) throw new Error("inflate: distance before the start");
      if (at + matchLength > size) throw new Error("inflate: more bytes than expected");
      if (distance >= matchLength) {
        out.copyWithin(at, at - distance, at - distance + matchLength);
        at += matchLength;
      } else {
        for (const end = at + matchLength; at < end; ++at) out[at] = out[at - distance];
      }
    }
    bits.pos = pos;
    bits.buffer = buffer;
    bits.count = count;
    return at;
  }

  return function inflate(input, size) {
    const out = new Uint8Array(size);
    const bits = new Bits(input);
    let at = 0;
    for (let last = 0; !last;) {
      last = bits.take(1);
      const type = bits.take(2);
      if (type === 0) {
        // Stored: the rest of this byte is skipped, then come LEN, its complement and LEN bytes.
        bits.pos -= bits.count >> 3;
        bits.buffer = 0;
        bits.count = 0;
        const pos = bits.pos;
        const length = input[pos] | (input[pos + 1] << 8);
        if ((length ^ (input[pos + 2] | (input[pos + 3] << 8))) !== 0xffff) throw new Error("inflate: bad stored block length");
        if (pos + 4 + length > input.length || at + length > size) throw new Error("inflate: stored block overruns");
        out.set(input.subarray(pos + 4, pos + 4 + length), at);
        bits.pos = pos + 4 + length;
        at += length;
      } else if (type === 1) {
        fixedCodes();
        at = inflateCodes(bits, out, at);
      } else if (type === 2) {
        dynamicCodes(bits);
        at = inflateCodes(bits, out, at);
      } else {
        throw new Error("inflate: reserved block type");
      }
    }
    if (bits.pos - (bits.count >> 3) > input.length) throw new Error("inflate: the stream ends early");
    if (at !== size) throw new Error("inflate: " + at + " bytes, expected " + size);
    return out;
  };
})();
