// @ts-check
// An MP4 / ISO-BMFF (ISO/IEC 14496-12) demuxer for the first video track, enough for
// WebCodecs: it reads the top-level box headers, the whole `moov` box and nothing of `mdat`,
// and returns the codec, the decoder configuration and every sample's place in the file.
// moov/trak/mdia/minf/stbl: stsd (avc1/avc3 + avcC, hvc1/hev1 + hvcC, vp09 + vpcC, vp08,
// av01 + av1C), stts (decode times), ctts (composition offsets), stsz, stsc + stco/co64 (where
// samples lie), stss (sync samples); mdhd (timescale), tkhd (size), edts/elst (the start).
// Fragmented files (moof) are refused.
import { BlobReader } from './blob-reader.js';
import { avcCodec, hevcCodec, vp9Codec, vpcCInfo, av1Codec } from './codec-string.js';
import { checkDuration, checkRate, checkSampleCount } from './demux-limits.js';

const TOP_LEVEL = new Set(['ftyp', 'styp', 'moov', 'mdat', 'free', 'skip', 'wide', 'pdin', 'uuid', 'meta', 'moof', 'mfra', 'sidx']);

/**
 * @param {Uint8Array} b
 * @param {number} i
 */
const fourcc = (b, i) => String.fromCharCode(b[i], b[i + 1], b[i + 2], b[i + 3]);

/**
 * Whether `head` (the first 12 bytes) looks like an ISO-BMFF file.
 * @param {Uint8Array} head
 */
export function isMp4(head) {
  return head.length >= 8 && TOP_LEVEL.has(fourcc(head, 4));
}

/** Big-endian reads within one box's bytes, with the box named in errors. */
class Box {
  /**
   * @param {Uint8Array} bytes
   * @param {string} type
   * @param {number} start
   * @param {number} end
   */
  constructor(bytes, type, start, end) {
    this.bytes = bytes;
    this.view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
    this.type = type;
    this.start = start; // first payload byte
    this.end = end;
  }

  /**
   * @param {number} at
   * @param {number} n
   */
  check(at, n) {
    if (at < this.start || at + n > this.end) {
      throw new Error(`the “${this.type}” box is too short (${this.end - this.start} bytes)`);
    }
  }

/** @param {number} at */
  u8(at) { this.check(at, 1); return this.bytes[at]; }
/** @param {number} at */
  u16(at) { this.check(at, 2); return this.view.getUint16(at); }
/** @param {number} at */
  u32(at) { this.check(at, 4); return this.view.getUint32(at); }
/** @param {number} at */
  i32(at) { this.check(at, 4); return this.view.getInt32(at); }
/** @param {number} at */
  u64(at) { this.check(at, 8); return Number(this.view.getBigUint64(at)); }
/** @param {number} at */
  i64(at) { this.check(at, 8); return Number(this.view.getBigInt64(at)); }
  payload(from = this.start) { return this.bytes.subarray(from, this.end); }

  /**
   * Number of `entrySize`-byte entries a table promises at `at`, checked against the box size.
   * @param {number} at
   * @param {number} entrySize
   */
  entries(at, entrySize) {
    const n = this.u32(at);
    if (n * entrySize > this.end - at - 4) {
      throw new Error(`the “${this.type}” box promises ${n} entries but holds ${Math.floor((this.end - at - 4) / entrySize)}`);
    }
    return n;
  }

  /** The child boxes in [from, end). */
  children(from = this.start) {
    /** @type {Box[]} */
    const out = [];
    for (let at = from; at < this.end;) {
      if (at + 8 > this.end) throw new Error(`a box inside “${this.type}” is cut short`);
      let size = this.view.getUint32(at);
      let header = 8;
      if (size === 1) {
        this.check(at + 8, 8);
        size = Number(this.view.getBigUint64(at + 8));
        header = 16;
      } else if (size === 0) {
        size = this.end - at;
      }
      const type = fourcc(this.bytes, at + 4);
      if (size < header || at + size > this.end) {
        throw new Error(`the “${type}” box inside “${this.type}” has a size (${size}) that does not fit`);
      }
      out.push(new Box(this.bytes, type, at + header, at + size));
      at += size;
    }
    return out;
  }

  /** @param {string} type */
  child(type) {
    return this.children().find((b) => b.type === type) ?? null;
  }

  /** @param {string} type */
  need(type) {
    const box = this.child(type);
    if (!box) throw new Error(`the “${this.type}” box has no “${type}” box`);
    return box;
  }
}

/** Walks the top-level boxes by their headers; returns the moov box's bytes. */
/** @param {BlobReader} reader */
async function readMoov(reader) {
  let moov = null;
  for (let pos = 0; pos < reader.size;) {
    const head = await reader.peek(pos, 16);
    if (head.length < 8) throw new Error(`the file is truncated: a box header at byte ${pos} is cut short`);
    const view = new DataView(head.buffer, head.byteOffset, head.byteLength);
    let size = view.getUint32(0);
    let header = 8;
    const type = fourcc(head, 4);
    if (size === 1) {
      if (head.length < 16) throw new Error(`the file is truncated: the “${type}” box header at byte ${pos}`);
      size = Number(view.getBigUint64(8));
      header = 16;
    } else if (size === 0) {
      size = reader.size - pos;
    }
    if (size < header) throw new Error(`the “${type}” box at byte ${pos} has an impossible size (${size})`);
    if (pos === 0 && !TOP_LEVEL.has(type)) throw new Error('not an MP4 file (no ftyp box at its start)');
    if (type === 'moof') throw new Error('fragmented MP4 (moof boxes) is not supported; remux it with `ffmpeg -i in.mp4 -c copy out.mp4`');
    if (type === 'moov') {
      moov = (await reader.read(pos + header, size - header, 'the moov box')).slice();
    }
    pos += size;
  }
  if (!moov) throw new Error('the file has no moov box (an incomplete recording or download?)');
  return new Box(moov, 'moov', 0, moov.length);
}

/**
 * The decoder configuration from the first sample entry of stsd.
 * @param {Box} stsd
 */
function sampleEntry(stsd) {
  const n = stsd.entries(stsd.start + 4, 8);
  if (n < 1) throw new Error('the video track has no sample description (stsd is empty)');
  const [entry] = stsd.children(stsd.start + 8);
  // VisualSampleEntry: 8 bytes of SampleEntry, 16 reserved, width, height, ..., then boxes at 78.
  const width = entry.u16(entry.start + 24);
  const height = entry.u16(entry.start + 26);
  const boxes = entry.children(entry.start + 78);
  /** @param {string} type */
  const record = (type) => {
    const box = boxes.find((b) => b.type === type);
    if (!box) throw new Error(`the “${entry.type}” sample entry has no “${type}” box`);
    return box;
  };
  const t = entry.type;
  if (t === 'avc1' || t === 'avc3') {
    const avcC = record('avcC').payload().slice();
    return { codec: avcCodec(avcC, t), description: avcC, width, height };
  }
  if (t === 'hvc1' || t === 'hev1') {
    const hvcC = record('hvcC').payload().slice();
    return { codec: hevcCodec(hvcC, t), description: hvcC, width, height };
  }
  if (t === 'vp09') {
    const vpcC = record('vpcC');
    return { codec: vp9Codec(vpcCInfo(vpcC.payload())), width, height };
  }
  if (t === 'vp08') return { codec: 'vp8', width, height };
  if (t === 'av01') return { codec: av1Codec(record('av1C').payload()), width, height };
  if (t === 'encv') throw new Error('the video is encrypted (encv)');
  throw new Error(`the video codec “${t}” is not one this reader knows (H.264, HEVC, VP8, VP9, AV1)`);
}

/**
 * Expands a run-length table (stts, ctts) of `entries` at `at` to `count` values.
 * @param {Box} box
 * @param {number} at
 * @param {number} count
 * @param {number} entrySize
 * @param {(at: number) => number} value
 */
function expandRuns(box, at, count, entrySize, value) {
  const n = box.entries(at, entrySize);
  /** @type {number[]} */
  const out = new Array(count);
  let i = 0;
  for (let k = 0; k < n; k++) {
    const run = box.u32(at + 4 + k * entrySize);
    const v = value(at + 8 + k * entrySize);
    if (i + run > count) throw new Error(`the “${box.type}” box describes more than the ${count} samples of stsz`);
    for (let r = 0; r < run; r++) out[i++] = v;
  }
  if (i !== count) throw new Error(`the “${box.type}” box describes ${i} samples, stsz ${count}`);
  return out;
}

/**
 * Sample sizes from stsz: at most MAX_SAMPLES, none empty, a constant size times the count
 * no more than the file (checked before anything the size of the table is allocated).
 * @param {Box} stbl
 * @param {number} fileSize
 * @returns {number[]}
 */
function sampleSizes(stbl, fileSize) {
  if (stbl.child('stz2')) throw new Error('compact sample sizes (stz2) are not supported');
  const stsz = stbl.need('stsz');
  const constant = stsz.u32(stsz.start + 4);
  if (constant) {
    const count = stsz.u32(stsz.start + 8);
    checkSampleCount(count, 'the stsz box');
    if (constant * count > fileSize) throw new Error(`stsz promises ${count} samples of ${constant} bytes, more than the file holds`);
    return new Array(count).fill(constant);
  }
  const count = stsz.entries(stsz.start + 8, 4);
  checkSampleCount(count, 'the stsz box');
  // The table itself lies in the file (4 bytes a frame); where the frames lie is checked
  // frame by frame, naming the first past the end.
  const sizes = new Array(count);
  for (let k = 0; k < count; k++) {
    sizes[k] = stsz.u32(stsz.start + 12 + 4 * k);
    if (sizes[k] === 0) throw new Error(`frame ${k + 1} of ${count} has a size of 0 bytes in the stsz box (the file is corrupt)`);
  }
  return sizes;
}

/**
 * Sample offsets in the file from stsc (samples per chunk) and stco/co64 (chunk offsets).
 * @param {Box} stbl
 * @param {number[]} sizes
 * @returns {number[]}
 */
function sampleOffsets(stbl, sizes) {
  const co64 = stbl.child('co64');
  const stco = co64 ?? stbl.need('stco');
  const chunks = stco.entries(stco.start + 4, co64 ? 8 : 4);
  /** @param {number} c */
  const chunkOffset = (c) => (co64 ? co64.u64(co64.start + 8 + 8 * c) : stco.u32(stco.start + 8 + 4 * c));
  const stsc = stbl.need('stsc');
  const runs = stsc.entries(stsc.start + 4, 12);
  const offsets = new Array(sizes.length);
  let s = 0;
  for (let r = 0; r < runs; r++) {
    const at = stsc.start + 8 + 12 * r;
    const first = stsc.u32(at) - 1;
    const perChunk = stsc.u32(at + 4);
    const last = r + 1 < runs ? stsc.u32(at + 12) - 1 : chunks;
    if (first < 0 || last > chunks || last < first) throw new Error('the stsc box names chunks that stco does not list');
    for (let c = first; c < last && s < sizes.length; c++) {
      let offset = chunkOffset(c);
      for (let k = 0; k < perChunk && s < sizes.length; k++) {
        offsets[s] = offset;
        offset += sizes[s++];
      }
    }
  }
  if (s !== sizes.length) throw new Error(`the stsc and stco boxes place ${s} samples, stsz has ${sizes.length}`);
  return offsets;
}

/** The media time where presentation starts and the delay before it (edts/elst), or none. */
/**
 * @param {Box} trak
 * @param {number} movieTimescale
 */
function editStart(trak, movieTimescale) {
  const elst = trak.child('edts')?.child('elst');
  if (!elst) return { shift: 0, delayUs: 0 };
  const v1 = elst.u8(elst.start) === 1;
  const n = elst.entries(elst.start + 4, v1 ? 20 : 12);
  let delayUs = 0;
  for (let k = 0; k < n; k++) {
    const at = elst.start + 8 + k * (v1 ? 20 : 12);
    const duration = v1 ? elst.u64(at) : elst.u32(at);
    const mediaTime = v1 ? elst.i64(at + 8) : elst.i32(at + 4);
    if (mediaTime === -1) delayUs += (duration * 1e6) / movieTimescale; // an empty edit
    else return { shift: mediaTime, delayUs };
  }
  return { shift: 0, delayUs };
}

/**
 * Demuxes the first video track of an MP4 `blob`. Returns { container, codec, description,
 * codedWidth, codedHeight, duration (s), fps, samples } with samples in decode order, each
 * { timestamp (µs, presentation), duration (µs), key, offset, size }. Throws a clear Error
 * for anything it cannot read.
 */
/** @param {Blob} blob */
export async function demuxMp4(blob) {
  const reader = new BlobReader(blob);
  const moov = await readMoov(reader);
  const mvhd = moov.need('mvhd');
  const movieTimescale = mvhd.u32(mvhd.start + (mvhd.u8(mvhd.start) === 1 ? 20 : 12));
  const trak = moov.children().filter((b) => b.type === 'trak').find((t) => {
    const hdlr = t.child('mdia')?.child('hdlr');
    return hdlr && fourcc(hdlr.bytes, hdlr.start + 8) === 'vide';
  });
  if (!trak) throw new Error('the file has no video track');
  const mdia = trak.need('mdia');
  const mdhd = mdia.need('mdhd');
  const v1 = mdhd.u8(mdhd.start) === 1;
  const timescale = mdhd.u32(mdhd.start + (v1 ? 20 : 12));
  const mediaDuration = v1 ? mdhd.u64(mdhd.start + 24) : mdhd.u32(mdhd.start + 16);
  if (!timescale || !movieTimescale) throw new Error('the video track has a zero timescale');
  const stbl = mdia.need('minf').need('stbl');
  const config = sampleEntry(stbl.need('stsd'));
  const tkhd = trak.need('tkhd');
  // tkhd ends with width and height, 16.16 fixed point: the display size.
  const displayWidth = Math.round(tkhd.u32(tkhd.end - 8) / 65536) || config.width;
  const displayHeight = Math.round(tkhd.u32(tkhd.end - 4) / 65536) || config.height;

  const sizes = sampleSizes(stbl, reader.size);
  const count = sizes.length;
  if (count === 0) throw new Error('the video track has no frames');
  const stts = stbl.need('stts');
  const deltas = expandRuns(stts, stts.start + 4, count, 8, (at) => stts.u32(at));
  const ctts = stbl.child('ctts');
  // ctts version 1 offsets are signed; version 0 ones are read signed too, as players do.
  const offsetsCt = ctts ? expandRuns(ctts, ctts.start + 4, count, 8, (at) => ctts.i32(at)) : null;
  const offsets = sampleOffsets(stbl, sizes);
  const stss = stbl.child('stss');
  const keys = stss ? new Set(Array.from({ length: stss.entries(stss.start + 4, 4) },
    (_, k) => stss.u32(stss.start + 8 + 4 * k) - 1)) : null;
  const { shift, delayUs } = editStart(trak, movieTimescale);

  /** @param {number} t */
  const us = (t) => Math.round((t * 1e6) / timescale);
  const samples = new Array(count);
  let dts = 0;
  for (let s = 0; s < count; s++) {
    if (offsets[s] + sizes[s] > reader.size) {
      throw new Error(`the file is truncated: frame ${s + 1} of ${count} lies at bytes ${offsets[s]}-`
        + `${offsets[s] + sizes[s]}, past its end at byte ${reader.size}`);
    }
    const cts = dts + (offsetsCt ? offsetsCt[s] : 0);
    samples[s] = {
      timestamp: us(cts - shift) + Math.round(delayUs), duration: us(deltas[s]),
      key: keys ? keys.has(s) : true, offset: offsets[s], size: sizes[s],
    };
    dts += deltas[s];
  }
  if (!samples[0].key) throw new Error('the first frame is not a keyframe');
  // The rate: the most common frame duration.
  const tally = new Map();
  for (const d of deltas) tally.set(d, (tally.get(d) ?? 0) + 1);
  const common = [...tally].sort((a, b) => b[1] - a[1])[0][0];
  const fps = common ? Math.round((100 * timescale) / common) / 100 : null;
  checkRate(fps, `the stts box (frames of ${common} ticks at ${timescale} a second)`);
  // mdhd's duration is all ones when unknown; the frames' own span is then the length.
  const unknown = v1 ? mediaDuration >= 2 ** 64 - 1 : mediaDuration === 0xffffffff;
  checkDuration(dts / timescale, 'the frames of the stts box last');
  const duration = (mediaDuration && !unknown ? mediaDuration : dts) / timescale;
  checkDuration(duration, 'the video track\'s duration in mdhd');
  return {
    container: 'mp4',
    codec: config.codec,
    description: config.description,
    codedWidth: config.width,
    codedHeight: config.height,
    displayWidth,
    displayHeight,
    duration,
    fps,
    samples,
  };
}
