// The demo's WebM/Matroska and MP4 demuxers (www/demux-webm.js, www/demux-mp4.js) on small
// videos made with ffmpeg at test time: every frame found, in decode order, with ffprobe's
// timestamps, keyframe flags and sizes; codec strings built from the codec records; broken
// and truncated files refused with a clear Error, never a hang.
import test from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync, rmSync, writeFileSync } from 'node:fs';
import { demuxWebm } from '../../www/demux-webm.js';
import { demuxMp4 } from '../../www/demux-mp4.js';
import { demux } from '../../www/webcodecs-source.js';
import { makeVideos, countFrames, packets, streamInfo, FRAMES, FPS } from './video-fixtures.mjs';

const videos = makeVideos();
test.after(() => rmSync(videos.dir, { recursive: true, force: true }));
const bytes = (name) => readFileSync(videos.path(name));
const blob = (buf) => new Blob([buf]);
const FRAME_US = 1e6 / FPS;

// Expected codec strings: profile and level from ffprobe where it knows them (VP9's level is
// the demuxer's default for 160x120, level 1.0, as ffmpeg writes none).
const CASES = {
  'vp9.webm': () => 'vp09.00.10.08',
  'vp9-10bit.webm': () => 'vp09.02.10.10',
  'vp8.webm': () => 'vp8',
  'av1.webm': (info) => `av01.0.${String(info.level).padStart(2, '0')}M.08`,
  'h264.mkv': (info) => `avc1.6400${info.level.toString(16).padStart(2, '0')}`,
  'h264.mp4': (info) => `avc1.6400${info.level.toString(16).padStart(2, '0')}`,
  'h264-faststart.mp4': () => 'avc1.64001e',
  'vp9.mp4': () => 'vp09.00.10.08',
  'av1.mp4': (info) => `av01.0.${String(info.level).padStart(2, '0')}M.08`,
  'hevc.mp4': (info) => `hvc1.1.6.L${info.level}.90`,
};

for (const [name, expected] of Object.entries(CASES)) {
  test(`${name}: every frame in decode order with ffprobe's timestamps, keyframes and sizes`, async () => {
    const track = await demux(blob(bytes(name)));
    const info = streamInfo(videos.path(name));
    assert.equal(track.container, name.endsWith('.mp4') ? 'mp4' : 'webm');
    assert.equal(track.codec, expected(info));
    assert.equal(countFrames(videos.path(name)), FRAMES, 'ffmpeg made the frames asked for');
    assert.equal(track.samples.length, FRAMES);
    const probed = packets(videos.path(name));
    assert.deepEqual(track.samples.map((s) => s.timestamp), probed.map((p) => p.pts), 'timestamps (µs)');
    assert.deepEqual(track.samples.map((s) => s.key), probed.map((p) => p.key), 'keyframe flags');
    assert.deepEqual(track.samples.map((s) => s.size), probed.map((p) => p.size), 'sizes');
    assert.ok(track.samples.filter((s) => s.key).length >= 3, 'a keyframe every 12 frames');
    // Presentation order is every 40 ms from 0, whatever the decode order.
    const shown = track.samples.map((s) => s.timestamp).sort((a, b) => a - b);
    assert.deepEqual(shown, Array.from({ length: FRAMES }, (_, k) => k * FRAME_US));
    assert.ok(track.samples.every((s) => s.duration === FRAME_US), 'every frame lasts 40 ms');
    assert.equal(track.fps, FPS);
    assert.ok(Math.abs(track.duration - FRAMES / FPS) < 1e-6, `duration ${track.duration}`);
    assert.deepEqual([track.codedWidth, track.codedHeight], [160, 120]);
    // The offsets point at the frames themselves: the first is the keyframe ffprobe reads.
    const file = bytes(name);
    assert.ok(track.samples.every((s) => s.offset + s.size <= file.length));
    const starts = new Set(track.samples.map((s) => s.offset));
    assert.equal(starts.size, FRAMES, 'no two frames at one offset');
    if (/h264|hevc/.test(name)) {
      assert.equal(track.description.length, Number(info.extradata_size), 'description is the avcC/hvcC record');
      assert.equal(track.description[0], 1, 'configurationVersion 1');
    } else {
      assert.equal(track.description, undefined);
    }
  });
}

test('H.264 with B-frames: decode order differs from presentation order', async () => {
  const { samples } = await demuxMp4(blob(bytes('h264.mp4')));
  const decodeOrder = samples.map((s) => s.timestamp);
  assert.notDeepEqual(decodeOrder, [...decodeOrder].sort((a, b) => a - b), 'ctts reorders frames');
  assert.equal(samples[0].timestamp, 0, 'the edit list starts presentation at 0');
});

/** Lengths of an EBML ID or size from its first byte. */
const vlen = (b) => Math.clz32(b) - 23;
function vsize(buf, at) {
  const n = vlen(buf[at]);
  let v = buf[at] & (0xff >> n);
  for (let k = 1; k < n; k++) v = v * 256 + buf[at + k];
  return { n, v };
}
const setUnknown = (buf, at, n) => { buf[at] = 0xff >> (n - 1); buf.fill(0xff, at + 1, at + n); };

/** The Segment's and every Cluster's size set to unknown, as MediaRecorder writes them. */
function unknownSizes(input) {
  const buf = Buffer.from(input);
  const header = vsize(buf, 4);
  let at = 4 + header.n + header.v;
  const segment = vsize(buf, at + 4);
  setUnknown(buf, at + 4, segment.n);
  for (at += 4 + segment.n; at < buf.length;) {
    const il = vlen(buf[at]);
    const id = buf.readUIntBE(at, il);
    const s = vsize(buf, at + il);
    if (id === 0x1f43b675) setUnknown(buf, at + il, s.n);
    at += il + s.n + s.v;
  }
  return buf;
}

/** A copy of `input` and the position of its first SimpleBlock's data. */
function firstSimpleBlock(input) {
  const buf = Buffer.from(input);
  let at = 0;
  for (;;) {
    const il = vlen(buf[at]);
    const id = buf.readUIntBE(at, il);
    const s = vsize(buf, at + il);
    if (id === 0xa3) return { buf, data: at + il + s.n };
    // Descend into the Segment and Clusters, skip everything else.
    at += il + s.n + (id === 0x18538067 || id === 0x1f43b675 ? 0 : s.v);
  }
}

test('WebM with a Segment and Clusters of unknown size (MediaRecorder style) reads the same', async () => {
  const original = await demuxWebm(blob(bytes('vp9.webm')));
  const changed = unknownSizes(bytes('vp9.webm'));
  assert.notDeepEqual(changed, bytes('vp9.webm'));
  const path = `${videos.dir}/unknown.webm`;
  writeFileSync(path, changed);
  assert.equal(countFrames(path), FRAMES, 'ffmpeg reads the rewritten file too');
  const track = await demuxWebm(blob(changed));
  assert.deepEqual(track.samples, original.samples);
  assert.equal(track.codec, original.codec);
});

test('laced video blocks are refused by name', async () => {
  const { buf, data } = firstSimpleBlock(bytes('vp9.webm'));
  buf[data + vlen(buf[data]) + 2] |= 0x02; // flags: Xiph lacing
  await assert.rejects(demuxWebm(blob(buf)), /uses lacing .*not supported/);
});

test('truncated files are refused with a clear Error', async () => {
  const cut = (name, share) => { const b = bytes(name); return blob(b.subarray(0, Math.floor(b.length * share))); };
  await assert.rejects(demuxWebm(cut('vp9.webm', 0.6)), /the file is truncated/);
  await assert.rejects(demuxWebm(cut('vp9.webm', 0.001)), /truncated|not a WebM/);
  // Unknown sizes too: the last block is cut.
  const unknown = unknownSizes(bytes('vp9.webm'));
  await assert.rejects(demuxWebm(blob(unknown.subarray(0, unknown.length - 3000))), /the file is truncated/);
  // moov at the end (ffmpeg's default): cut, there is no moov.
  await assert.rejects(demuxMp4(cut('h264.mp4', 0.7)), /no moov box/);
  // moov first: the frames past the cut are named.
  await assert.rejects(demuxMp4(cut('h264-faststart.mp4', 0.7)), /the file is truncated: frame \d+ of 37 lies at bytes/);
});

test('corrupt and foreign files are refused with a clear Error', async () => {
  await assert.rejects(demux(blob(Buffer.from('this is a text file, not a video\n'))), /not a WebM, Matroska or MP4 file/);
  await assert.rejects(demux(blob(Buffer.alloc(0))), /not a WebM, Matroska or MP4 file/);
  await assert.rejects(demux(blob(bytes('mpeg4.mp4'))), /the video codec “mp4v” is not one this reader knows/);
  // stsz says 36 frames, stts times 37.
  const mp4 = Buffer.from(bytes('h264-faststart.mp4'));
  const stsz = mp4.indexOf('stsz');
  mp4.writeUInt32BE(36, stsz + 12);
  await assert.rejects(demuxMp4(blob(mp4)), /the “stts” box describes more than the 36 samples of stsz/);
  // A top-level box of size 4 (less than its own header).
  const tiny = Buffer.from(bytes('h264.mp4'));
  tiny.writeUInt32BE(4, 0);
  await assert.rejects(demuxMp4(blob(tiny)), /the “ftyp” box at byte 0 has an impossible size \(4\)/);
  // An element ID that cannot exist (a zero byte) where the Segment should start.
  const webm = Buffer.from(bytes('vp9.webm'));
  const seg = webm.indexOf(Buffer.from([0x18, 0x53, 0x80, 0x67]));
  webm[seg] = 0;
  await assert.rejects(demuxWebm(blob(webm)), /not a valid WebM element ID at byte \d+/);
});

test('random damage to the headers ends in a result inside the file or an Error, never a hang', async () => {
  let seed = 12345;
  const rand = (n) => { seed = (seed * 1103515245 + 12345) % 2147483648; return seed % n; };
  for (const name of ['vp9.webm', 'h264.mkv', 'h264-faststart.mp4', 'av1.mp4']) {
    const original = bytes(name);
    // The headers: WebM's come first; MP4's are the moov box, wherever it is.
    const moov = original.indexOf('moov') - 4;
    const [from, span] = name.endsWith('.mp4') ? [moov, original.readUInt32BE(moov)] : [0, 2500];
    let refused = 0;
    for (let trial = 0; trial < 150; trial++) {
      const buf = Buffer.from(original);
      for (let k = 0; k < 3; k++) buf[from + rand(span)] = rand(256);
      const outcome = await Promise.race([
        demux(blob(buf)).then((t) => t, (err) => err),
        new Promise((resolve) => setTimeout(() => resolve('hang'), 5000)),
      ]);
      assert.notEqual(outcome, 'hang', `${name} trial ${trial} hung`);
      if (outcome instanceof Error) {
        refused++;
        assert.ok(outcome.message.length > 10, `${name} trial ${trial}: ${outcome.message}`);
      } else {
        assert.ok(outcome.samples.length > 0 && outcome.samples.every((s) => s.offset >= 0 && s.size >= 0
          && s.offset + s.size <= buf.length && Number.isFinite(s.timestamp)), `${name} trial ${trial}: samples inside the file`);
      }
    }
    assert.ok(refused > 0, `${name}: some damage is noticed`);
  }
});

// Issue 19: tables and clocks that would take gigabytes, minutes or give absurd values.

/** An EBML element: its ID's bytes, an 8-byte size (or unknown), the payload. */
function el(id, ...parts) {
  const payload = Buffer.concat(parts.map((p) => (Buffer.isBuffer(p) ? p : Buffer.from(p))));
  const idBytes = Buffer.from(id.toString(16).padStart(2 * Math.ceil(id.toString(16).length / 2), '0'), 'hex');
  const size = Buffer.alloc(8);
  size.writeBigUInt64BE(BigInt(payload.length));
  size[0] = 0x01;
  return Buffer.concat([idBytes, size, payload]);
}
const u = (v, n = 4) => { const b = Buffer.alloc(8); b.writeBigUInt64BE(BigInt(v)); return b.subarray(8 - n); };
const f64 = (v) => { const b = Buffer.alloc(8); b.writeDoubleBE(v); return b; };
/** A SimpleBlock of track 1 at `rel` ms holding `data`. */
const simpleBlock = (rel, data, key = true) => el(0xa3, Buffer.from([0x81, (rel >> 8) & 0xff, rel & 0xff, key ? 0x80 : 0]), data);

/** A small VP8 WebM: `info` children, `track` children added, a cluster of `blocks`, `more`. */
function webm({ info = [], track = [], blocks = [simpleBlock(0, [1, 2, 3]), simpleBlock(40, [4, 5], false)], more = [] } = {}) {
  return Buffer.concat([
    el(0x1a45dfa3, el(0x4282, 'webm')),
    el(0x18538067,
      el(0x1549a966, ...info),
      el(0x1654ae6b, el(0xae, el(0xd7, u(1, 1)), el(0x83, u(1, 1)), el(0x86, 'V_VP8'),
        el(0xe0, el(0xb0, u(160, 2)), el(0xba, u(120, 2))), ...track)),
      el(0x1f43b675, el(0xe7, u(0, 1)), ...blocks), ...more),
  ]);
}

test('the hand-made WebM of these tests reads', async () => {
  const t = await demuxWebm(blob(webm({ info: [el(0x2ad7b1, u(1e6)), el(0x4489, f64(80))] })));
  assert.deepEqual(t.samples.map((s) => [s.timestamp, s.size, s.key]), [[0, 3, true], [40000, 2, false]]);
  assert.equal(t.fps, 25);
  assert.equal(t.duration, 0.08);
});

test('WebM: zero-size blocks, absurd Duration, TimecodeScale and frame rates are refused', async () => {
  await assert.rejects(demuxWebm(blob(webm({ blocks: [simpleBlock(0, [1]), simpleBlock(40, [])] }))),
    /the block at byte \d+ holds no frame data/);
  // 3 million empty blocks: refused at the first, not after 34 s and 1.3 GB.
  const empty = simpleBlock(0, []);
  const many = webm({ blocks: [simpleBlock(0, [1]), Buffer.concat(Array(3_000_000).fill(empty))] });
  const started = Date.now();
  await assert.rejects(demuxWebm(blob(many)), /holds no frame data/);
  assert.ok(Date.now() - started < 20_000);
  for (const [duration, name] of [[Infinity, 'Infinity'], [-5, '-5'], [NaN, 'NaN']]) {
    await assert.rejects(demuxWebm(blob(webm({ info: [el(0x4489, f64(duration))] }))),
      new RegExp(`the Info element's Duration \\(${name}\\) is not a length of time`));
  }
  // 10^12 ms: 31 years.
  await assert.rejects(demuxWebm(blob(webm({ info: [el(0x4489, f64(1e12))] }))),
    /the Info element's Duration \(1000000000 s\) is not a video's length: it must be 0 to 604800 s/);
  await assert.rejects(demuxWebm(blob(webm({ info: [el(0x2ad7b1, Buffer.alloc(8, 0xff))] }))),
    /TimecodeScale \(18446744073709552000 ns a tick\) is not 1 ns to 1 s/);
  await assert.rejects(demuxWebm(blob(webm({ info: [el(0x2ad7b1, u(0))] }))), /TimecodeScale \(0 ns a tick\)/);
  // A frame every 2^50 ns (13 days): a frame rate of 0.
  await assert.rejects(demuxWebm(blob(webm({ track: [el(0x23e383, u(2 ** 50, 8))] }))),
    /the track's DefaultDuration gives a frame rate of 0 fps/);
  // A second Cluster 10^12 ms later: no video spans 31 years.
  const far = webm({ more: [el(0x1f43b675, el(0xe7, u(1e12, 8)), simpleBlock(0, [9]))] });
  await assert.rejects(demuxWebm(blob(far)), /not a video's length/);
});

/** h264-faststart.mp4 with its tables edited by `edit(buf, at)` (`at`: box positions). */
function editedMp4(edit) {
  const buf = Buffer.from(bytes('h264-faststart.mp4'));
  const at = (type) => buf.indexOf(type) - 4;
  edit(buf, at);
  return buf;
}

test('MP4: 20 million one-byte samples, empty samples and absurd clocks are refused', async () => {
  // stsz: a constant size of 1 byte for 20 million samples; stts and stsc agree; the file is
  // padded to 21 MB so that the sizes fit in it.
  const table = editedMp4((buf, at) => {
    buf.writeUInt32BE(1, at('stsz') + 12);
    buf.writeUInt32BE(20_000_000, at('stsz') + 16);
    buf.writeUInt32BE(1, at('stts') + 12);
    buf.writeUInt32BE(20_000_000, at('stts') + 16);
    buf.writeUInt32BE(1, at('stsc') + 12);
    buf.writeUInt32BE(1, at('stsc') + 16);
    buf.writeUInt32BE(20_000_000, at('stsc') + 20);
  });
  const pad = Buffer.alloc(21_000_000);
  pad.writeUInt32BE(pad.length, 0);
  pad.write('free', 4);
  await assert.rejects(demuxMp4(blob(Buffer.concat([table, pad]))),
    /the stsz box declares 20000000 frames, more than the 1000000 this reader accepts/);
  const empty = editedMp4((buf, at) => buf.writeUInt32BE(0, at('stsz') + 20 + 4 * 3));
  await assert.rejects(demuxMp4(blob(empty)), /frame 4 of 37 has a size of 0 bytes in the stsz box/);
  // Every frame 2^32 - 1 ticks long at 1 tick a second: 136 years, 0 fps.
  const slow = editedMp4((buf, at) => {
    const mdhd = at('mdhd');
    buf.writeUInt32BE(1, mdhd + 8 + (buf[mdhd + 8] === 1 ? 20 : 12));
    buf.writeUInt32BE(0xffffffff, at('stts') + 20);
  });
  await assert.rejects(demuxMp4(blob(slow)), /gives a frame rate of 0 fps/);
});
