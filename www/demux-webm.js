// @ts-check
// A WebM / Matroska demuxer for the first video track, enough for WebCodecs. It walks the EBML
// element headers: EBML header (DocType) -> Segment -> Info (TimecodeScale, Duration), Tracks
// (TrackEntry: TrackNumber, TrackType, CodecID, CodecPrivate, DefaultDuration, Video:
// PixelWidth/Height), Cluster (Timecode, SimpleBlock, BlockGroup: Block, BlockDuration,
// ReferenceBlock). Block payloads are not read, only their place in the file. Segments and
// Clusters of unknown size (as MediaRecorder writes them) end where an element that cannot be
// their child begins. Laced video blocks and encoded (compressed, encrypted) tracks are refused.
import { BlobReader, TruncatedError } from './blob-reader.js';
import { avcCodec, hevcCodec, vp9Codec, vp9FrameInfo, vp9Level, vp9PrivateInfo, av1Codec } from './codec-string.js';
import { MAX_SAMPLES, checkDuration, checkRate, checkSampleCount } from './demux-limits.js';

const ID = {
  EBML: 0x1a45dfa3, DocType: 0x4282, Segment: 0x18538067, Info: 0x1549a966, TimecodeScale: 0x2ad7b1,
  Duration: 0x4489, Tracks: 0x1654ae6b, TrackEntry: 0xae, TrackNumber: 0xd7, TrackType: 0x83,
  CodecID: 0x86, CodecPrivate: 0x63a2, DefaultDuration: 0x23e383, Video: 0xe0, PixelWidth: 0xb0,
  PixelHeight: 0xba, ContentEncodings: 0x6d80, Cluster: 0x1f43b675, Timecode: 0xe7,
  SimpleBlock: 0xa3, BlockGroup: 0xa0, Block: 0xa1, BlockDuration: 0x9b, ReferenceBlock: 0xfb,
};
// What a Cluster may hold (Timecode, SilentTracks, Position, PrevSize, SimpleBlock, BlockGroup,
// EncryptedBlock, Void, CRC-32): anything else ends a Cluster of unknown size.
const CLUSTER_CHILDREN = new Set([0xe7, 0x5854, 0xa7, 0xab, 0xa3, 0xa0, 0xaf, 0xec, 0xbf]);

// Most blocks of all tracks together (audio has more blocks a second than video).
const MAX_BLOCKS = 4 * MAX_SAMPLES;

/** @param {number} id */
const hex = (id) => `0x${id.toString(16).toUpperCase()}`;

/**
 * Whether `head` starts with the EBML magic.
 * @param {Uint8Array} head
 */
export function isWebm(head) {
  return head.length >= 4 && head[0] === 0x1a && head[1] === 0x45 && head[2] === 0xdf && head[3] === 0xa3;
}

/**
 * The element header at bytes[at] (file position `pos`): { id, size (null: unknown), start
 * (file position of the data) }. The ID keeps its length marker; the size drops it.
 * @param {Uint8Array} bytes
 * @param {number} at
 * @param {number} pos
 */
function parseHeader(bytes, at, pos) {
  const cut = () => new TruncatedError(`the file is truncated: the element header at byte ${pos} is cut short`);
  if (at >= bytes.length) throw cut();
  const idLen = Math.clz32(bytes[at]) - 23;
  if (idLen < 1 || idLen > 4) throw new Error(`not a valid WebM element ID at byte ${pos} (the file is corrupt)`);
  if (at + idLen >= bytes.length) throw cut();
  let id = 0;
  for (let k = 0; k < idLen; k++) id = id * 256 + bytes[at + k];
  const first = bytes[at + idLen];
  const sizeLen = Math.clz32(first) - 23;
  if (sizeLen < 1 || sizeLen > 8) throw new Error(`element ${hex(id)} at byte ${pos} has no valid size (the file is corrupt)`);
  if (at + idLen + sizeLen > bytes.length) throw cut();
  let size = first & (0xff >> sizeLen);
  let allOnes = size === 0xff >> sizeLen;
  for (let k = 1; k < sizeLen; k++) {
    const b = bytes[at + idLen + k];
    size = size * 256 + b;
    allOnes &&= b === 0xff;
  }
  return { id, size: allOnes ? null : size, start: pos + idLen + sizeLen };
}

/**
 * @param {BlobReader} reader
 * @param {number} pos
 */
async function headerAt(reader, pos) {
  return parseHeader(await reader.peek(pos, 12), 0, pos);
}

/**
 * The children of an element held in memory (`bytes` starts at file position `base`).
 * @param {Uint8Array} bytes
 * @param {number} base
 * @param {number} [from]
 * @param {number} [to]
 */
function* children(bytes, base, from = 0, to = bytes.length) {
  for (let at = from; at < to;) {
    const h = parseHeader(bytes.subarray(0, to), at, base + at);
    if (h.size === null) throw new Error(`element ${hex(h.id)} at byte ${base + at} has an unknown size where it must be known`);
    const start = h.start - base;
    if (start + h.size > to) throw new Error(`element ${hex(h.id)} at byte ${base + at} overruns its parent (the file is corrupt)`);
    yield { id: h.id, data: bytes.subarray(start, start + h.size), pos: h.start };
    at = start + h.size;
  }
}

/** @param {Uint8Array} data */
function uint(data) {
  if (data.length > 8) throw new Error('an unsigned integer element is longer than 8 bytes');
  let v = 0;
  for (const b of data) v = v * 256 + b;
  return v;
}

/** @param {Uint8Array} data */
function float(data) {
  const view = new DataView(data.buffer, data.byteOffset, data.byteLength);
  if (data.length === 4) return view.getFloat32(0);
  if (data.length === 8) return view.getFloat64(0);
  if (data.length === 0) return 0;
  throw new Error(`a float element has ${data.length} bytes`);
}

/** @typedef {{ scale: number, duration: number | null }} Info */

/**
 * @param {Uint8Array} bytes
 * @param {number} base
 * @returns {Info}
 */
function parseInfo(bytes, base) {
  /** @type {Info} */
  const info = { scale: 1e6, duration: null };
  for (const e of children(bytes, base)) {
    if (e.id === ID.TimecodeScale) info.scale = uint(e.data);
    if (e.id === ID.Duration) info.duration = float(e.data);
  }
  // TimecodeScale is nanoseconds per tick (1e6 by default): 1 ns to 1 s is a clock.
  if (!(info.scale >= 1 && info.scale <= 1e9)) {
    throw new Error(`the Info element's TimecodeScale (${info.scale} ns a tick) is not 1 ns to 1 s (the file is corrupt)`);
  }
  if (info.duration !== null) {
    if (!(info.duration >= 0 && info.duration < Infinity)) {
      throw new Error(`the Info element's Duration (${info.duration}) is not a length of time (the file is corrupt)`);
    }
    checkDuration((info.duration * info.scale) / 1e9, 'the Info element\'s Duration');
    if (info.duration === 0) info.duration = null;
  }
  return info;
}

/**
 * @param {Uint8Array} bytes
 * @param {number} base
 */
function parseTracks(bytes, base) {
  const tracks = [];
  for (const entry of children(bytes, base)) {
    if (entry.id !== ID.TrackEntry) continue;
    /**
     * @type {{ number: number | null, type: number | null, codecId: string, codecPrivate: Uint8Array | null,
     *   defaultDuration: number | null, width: number, height: number, encoded: boolean }}
     */
    const t = { number: null, type: null, codecId: '', codecPrivate: null, defaultDuration: null, width: 0, height: 0, encoded: false };
    for (const e of children(entry.data, entry.pos)) {
      if (e.id === ID.TrackNumber) t.number = uint(e.data);
      else if (e.id === ID.TrackType) t.type = uint(e.data);
      else if (e.id === ID.CodecID) t.codecId = new TextDecoder().decode(e.data).replace(/\0+$/, '');
      else if (e.id === ID.CodecPrivate) t.codecPrivate = e.data.slice();
      else if (e.id === ID.DefaultDuration) t.defaultDuration = uint(e.data);
      else if (e.id === ID.ContentEncodings) t.encoded = true;
      else if (e.id === ID.Video) {
        for (const v of children(e.data, e.pos)) {
          if (v.id === ID.PixelWidth) t.width = uint(v.data);
          if (v.id === ID.PixelHeight) t.height = uint(v.data);
        }
      }
    }
    tracks.push(t);
  }
  return tracks;
}

/**
 * A Block's or SimpleBlock's head: track number, relative timecode, flags, head length.
 * @param {Uint8Array} bytes
 * @param {number} pos
 */
function blockHead(bytes, pos) {
  const n = bytes[0] ? Math.clz32(bytes[0]) - 23 : 9;
  if (n < 1 || n > 8 || bytes.length < n + 3) throw new Error(`the block at byte ${pos} has a malformed head (the file is corrupt)`);
  let track = bytes[0] & (0xff >> n);
  for (let k = 1; k < n; k++) track = track * 256 + bytes[k];
  const rel = (bytes[n] << 24 >> 16) | bytes[n + 1]; // signed 16-bit
  return { track, rel, flags: bytes[n + 2], length: n + 3 };
}

/**
 * A block of the file: its track, time (ticks), keyframe, BlockDuration, lacing and frame bytes.
 * @typedef {{ track: number, time: number, key: boolean, duration: number | null, laced: boolean,
 *   offset: number, size: number }} Block
 */

/**
 * Reads one Cluster's blocks into `blocks`; returns the position after the Cluster.
 * @param {BlobReader} reader
 * @param {{ size: number | null, start: number }} cluster
 * @param {number} parentEnd
 * @param {Block[]} blocks
 */
async function readCluster(reader, cluster, parentEnd, blocks) {
  const end = cluster.size === null ? parentEnd : cluster.start + cluster.size;
  let timecode = null;
  let pos = cluster.start;
  while (pos < end) {
    const h = await headerAt(reader, pos);
    if (cluster.size === null && !CLUSTER_CHILDREN.has(h.id)) return pos;
    if (h.size === null) throw new Error(`element ${hex(h.id)} at byte ${pos} in a Cluster has an unknown size`);
    const stop = h.start + h.size;
    if (stop > reader.size) {
      throw new TruncatedError(`the file is truncated: element ${hex(h.id)} at byte ${pos} ends at byte ${stop}, past the file's end at byte ${reader.size}`);
    }
    if (stop > end) throw new Error(`element ${hex(h.id)} at byte ${pos} overruns its Cluster (the file is corrupt)`);
    if (h.id === ID.Timecode) {
      timecode = uint(await reader.read(h.start, h.size, 'a Cluster Timecode'));
    } else if (h.id === ID.SimpleBlock || h.id === ID.BlockGroup) {
      if (timecode === null) throw new Error(`the block at byte ${pos} comes before its Cluster's Timecode`);
      let block;
      if (h.id === ID.SimpleBlock) {
        const head = blockHead(await reader.read(h.start, Math.min(h.size, 11)), pos);
        block = { ...head, start: h.start, size: h.size, key: (head.flags & 0x80) !== 0, duration: null };
      } else {
        /** @type {(ReturnType<typeof blockHead> & { start: number, size: number }) | null} */
        let found = null;
        let key = true;
        /** @type {number | null} */
        let duration = null;
        for (const e of children(await reader.read(h.start, h.size, 'a BlockGroup'), h.start)) {
          if (e.id === ID.Block) found = { ...blockHead(e.data.subarray(0, 11), e.pos), start: e.pos, size: e.data.length };
          if (e.id === ID.BlockDuration) duration = uint(e.data);
          if (e.id === ID.ReferenceBlock) key = false;
        }
        if (!found) throw new Error(`the BlockGroup at byte ${pos} has no Block`);
        block = { ...found, key, duration };
      }
      if (block.size <= block.length) throw new Error(`the block at byte ${pos} holds no frame data (the file is corrupt)`);
      if (blocks.length >= MAX_BLOCKS) throw new Error(`the file has more than ${MAX_BLOCKS} blocks, more than this reader accepts`);
      blocks.push({
        track: block.track, time: timecode + block.rel, key: block.key, duration: block.duration,
        laced: (block.flags & 0x06) !== 0, offset: block.start + block.length, size: block.size - block.length,
      });
    }
    pos = stop;
  }
  return pos;
}

/** The codec string and description for a track, reading the first keyframe where needed. */
/**
 * @param {ReturnType<typeof parseTracks>[number]} track
 * @param {BlobReader} reader
 * @param {{ offset: number, size: number }} first the first sample
 * @returns {Promise<{ codec: string, description?: Uint8Array | null }>}
 */
async function decoderConfig(track, reader, first) {
  const p = track.codecPrivate;
  const needPrivate = () => {
    if (!p) throw new Error(`the ${track.codecId} track has no CodecPrivate`);
    return p;
  };
  switch (track.codecId) {
    case 'V_VP8': return { codec: 'vp8' };
    case 'V_VP9': {
      // Matroska's VP9 CodecPrivate is optional; the first keyframe's header gives the rest.
      const given = p ? vp9PrivateInfo(p) : {};
      const header = given.profile === undefined || given.bitDepth === undefined
        ? vp9FrameInfo(await reader.read(first.offset, Math.min(first.size, 16), 'the first frame')) : null;
      const profile = given.profile ?? header?.profile;
      const bitDepth = given.bitDepth ?? header?.bitDepth;
      // (The keyframe's header gives both when the CodecPrivate does not.)
      if (profile === undefined || bitDepth === undefined) throw new Error('the VP9 track gives no profile or bit depth');
      return {
        codec: vp9Codec({ profile, level: given.level || vp9Level(track.width, track.height), bitDepth }),
      };
    }
    case 'V_AV1': return { codec: av1Codec(needPrivate()) };
    case 'V_MPEG4/ISO/AVC': return { codec: avcCodec(needPrivate()), description: p };
    case 'V_MPEGH/ISO/HEVC': return { codec: hevcCodec(needPrivate()), description: p };
    default:
      throw new Error(`the video codec “${track.codecId}” is not one this reader knows (VP8, VP9, AV1, H.264, HEVC)`);
  }
}

/**
 * Demuxes the first video track of a WebM/Matroska `blob`. Returns { container, codec,
 * description, codedWidth, codedHeight, duration (s), fps, samples } with samples in decode
 * order, each { timestamp (µs), duration (µs), key, offset, size }. Throws a clear Error for
 * anything it cannot read.
 */
/** @param {Blob} blob */
export async function demuxWebm(blob) {
  const reader = new BlobReader(blob);
  const ebml = await headerAt(reader, 0);
  if (ebml.id !== ID.EBML || ebml.size === null) throw new Error('not a WebM or Matroska file (no EBML header)');
  let docType = 'matroska';
  for (const e of children(await reader.read(ebml.start, ebml.size, 'the EBML header'), ebml.start)) {
    if (e.id === ID.DocType) docType = new TextDecoder().decode(e.data).replace(/\0+$/, '');
  }
  if (docType !== 'webm' && docType !== 'matroska') throw new Error(`the EBML file is a “${docType}”, not WebM or Matroska`);
  let pos = ebml.start + ebml.size;
  const segment = await headerAt(reader, pos);
  if (segment.id !== ID.Segment) throw new Error(`the file has no Segment after its EBML header (element ${hex(segment.id)})`);
  const end = segment.size === null ? reader.size : segment.start + segment.size;
  if (end > reader.size) {
    throw new TruncatedError(`the file is truncated: its Segment ends at byte ${end}, the file at byte ${reader.size}`);
  }
  /** @type {Info} */
  let info = { scale: 1e6, duration: null };
  /** @type {ReturnType<typeof parseTracks>} */
  let tracks = [];
  /** @type {Block[]} */
  const blocks = [];
  for (pos = segment.start; pos < end;) {
    const h = await headerAt(reader, pos);
    if (h.id === ID.Cluster) {
      pos = await readCluster(reader, h, end, blocks);
      continue;
    }
    if (h.id === ID.EBML || h.id === ID.Segment) break; // a second file appended: read the first
    if (h.size === null) throw new Error(`element ${hex(h.id)} at byte ${pos} has an unknown size; only a Segment or Cluster may`);
    if (h.start + h.size > end) throw new Error(`element ${hex(h.id)} at byte ${pos} overruns its Segment (the file is corrupt or truncated)`);
    if (h.id === ID.Info) info = parseInfo(await reader.read(h.start, h.size, 'the Info element'), h.start);
    if (h.id === ID.Tracks) tracks = parseTracks(await reader.read(h.start, h.size, 'the Tracks element'), h.start);
    pos = h.start + h.size;
  }

  const track = tracks.find((t) => t.type === 1);
  if (!track) throw new Error('the file has no video track');
  if (track.encoded) throw new Error('the video track is compressed or encrypted (ContentEncodings), which is not supported');
  const mine = blocks.filter((b) => b.track === track.number);
  if (mine.length === 0) throw new Error('the video track has no frames');
  checkSampleCount(mine.length, 'the video track');
  if (mine.some((b) => b.laced)) throw new Error('the video track uses lacing (several frames per block), which is not supported');
  if (!mine[0].key) throw new Error('the first frame is not a keyframe');

  /** @param {number} units */
  const us = (units) => Math.round((units * info.scale) / 1000);
  /** @type {{ timestamp: number, duration: number, key: boolean, offset: number, size: number, blockDuration?: number | null }[]} */
  const samples = mine.map((b) => ({ timestamp: us(b.time), duration: 0, key: b.key, offset: b.offset, size: b.size, blockDuration: b.duration }));
  // Durations: DefaultDuration (ns), else BlockDuration, else the gap to the next frame shown.
  const shown = [...samples].sort((a, b) => a.timestamp - b.timestamp);
  const gaps = shown.slice(1).map((s, k) => s.timestamp - shown[k].timestamp);
  const median = gaps.length ? [...gaps].sort((a, b) => a - b)[gaps.length >> 1] : null;
  const endUs = info.duration ? us(info.duration) : null;
  shown.forEach((s, k) => {
    if (track.defaultDuration) s.duration = Math.round(track.defaultDuration / 1000);
    else if (typeof s.blockDuration === 'number') s.duration = us(s.blockDuration);
    else if (k + 1 < shown.length) s.duration = gaps[k];
    else s.duration = endUs !== null && endUs > s.timestamp ? endUs - s.timestamp : median ?? 0;
  });
  for (const s of samples) delete s.blockDuration;
  const last = shown[shown.length - 1];
  checkDuration(Math.abs(shown[0].timestamp) / 1e6, 'the first frame\'s timestamp');
  checkDuration((last.timestamp - shown[0].timestamp) / 1e6, 'the frames\' timestamps span');
  const frameNs = track.defaultDuration || (median ? median * 1000 : null);
  const fps = frameNs ? Math.round(1e11 / frameNs) / 100 : null;
  checkRate(fps, track.defaultDuration ? 'the track\'s DefaultDuration' : 'the frames\' timestamps');
  return {
    container: 'webm',
    ...(await decoderConfig(track, reader, samples[0])),
    codedWidth: track.width,
    codedHeight: track.height,
    displayWidth: track.width,
    displayHeight: track.height,
    duration: (endUs ?? last.timestamp + last.duration) / 1e6,
    fps,
    samples,
  };
}
