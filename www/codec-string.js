// @ts-check
// Codec strings for `VideoDecoder.configure`, built from the codec configuration records the
// containers carry (the same records in MP4 boxes and in Matroska's CodecPrivate): avcC for
// H.264, hvcC for HEVC, vpcC (or Matroska's VP9 feature list, or the first keyframe's header)
// for VP9, av1C for AV1. See the WebCodecs codec registry.

/** @param {number} v */
const hex2 = (v) => v.toString(16).padStart(2, '0');
/** @param {number} v */
const dec2 = (v) => String(v).padStart(2, '0');

/**
 * @param {Uint8Array} bytes
 * @param {number} n
 * @param {string} what
 */
function need(bytes, n, what) {
  if (bytes.length < n) throw new Error(`the ${what} record is too short (${bytes.length} bytes, needs ${n})`);
}

/**
 * `avc1.PPCCLL` from an AVCDecoderConfigurationRecord (avcC): profile, constraints, level.
 * @param {Uint8Array} avcC
 * @param {string} [fourcc]
 */
export function avcCodec(avcC, fourcc = 'avc1') {
  need(avcC, 7, 'avcC');
  if (avcC[0] !== 1) throw new Error(`the avcC record has version ${avcC[0]}, not 1`);
  return `${fourcc}.${hex2(avcC[1])}${hex2(avcC[2])}${hex2(avcC[3])}`;
}

/**
 * `hvc1.P.C.TL.B...` from an HEVCDecoderConfigurationRecord (hvcC): profile space and idc, the
 * compatibility flags bit-reversed, tier and level, the constraint bytes without trailing zeros.
 * @param {Uint8Array} hvcC
 * @param {string} [fourcc]
 */
export function hevcCodec(hvcC, fourcc = 'hvc1') {
  need(hvcC, 13, 'hvcC');
  const space = hvcC[1] >> 6;
  const tier = (hvcC[1] >> 5) & 1;
  const idc = hvcC[1] & 0x1f;
  let compat = (hvcC[2] << 24 | hvcC[3] << 16 | hvcC[4] << 8 | hvcC[5]) >>> 0;
  let reversed = 0;
  for (let b = 0; b < 32; b++, compat >>>= 1) reversed = (reversed << 1 | (compat & 1)) >>> 0;
  const constraints = Array.from(hvcC.subarray(6, 12));
  while (constraints.length && constraints.at(-1) === 0) constraints.pop();
  const prefix = space ? String.fromCharCode(64 + space) : '';
  return [`${fourcc}`, `${prefix}${idc}`, reversed.toString(16), `${tier ? 'H' : 'L'}${hvcC[12]}`,
    ...constraints.map((c) => c.toString(16).toUpperCase())].join('.');
}

/**
 * `vp09.PP.LL.DD`: profile, level (10 for 1.0, ...), bit depth.
 * @param {{ profile: number, level: number, bitDepth: number }} info
 */
export function vp9Codec({ profile, level, bitDepth }) {
  return `vp09.${dec2(profile)}.${dec2(level)}.${dec2(bitDepth)}`;
}

/**
 * Profile, level and bit depth from a VPCodecConfigurationRecord box's payload (vpcC, version 1).
 * @param {Uint8Array} vpcC
 */
export function vpcCInfo(vpcC) {
  need(vpcC, 12, 'vpcC');
  if (vpcC[0] !== 1) throw new Error(`the vpcC box has version ${vpcC[0]}; only version 1 is read`);
  return { profile: vpcC[4], level: vpcC[5], bitDepth: vpcC[6] >> 4 };
}

/**
 * The smallest VP9 level whose largest picture holds width x height (a default when none is given).
 * @param {number} width
 * @param {number} height
 */
export function vp9Level(width, height) {
  const levels = [[10, 36864], [11, 73728], [20, 122880], [21, 245760], [30, 552960], [31, 983040],
    [40, 2228224], [50, 8912896], [60, 35651584]];
  return (levels.find(([, max]) => width * height <= max) ?? [62])[0];
}

/**
 * Matroska's VP9 CodecPrivate: ID-length-value features (1 profile, 2 level, 3 bit depth).
 * @param {Uint8Array} bytes
 */
export function vp9PrivateInfo(bytes) {
  /** @type {{ profile?: number, level?: number, bitDepth?: number }} */
  const info = {};
  for (let i = 0; i + 2 <= bytes.length;) {
    const [id, len] = [bytes[i], bytes[i + 1]];
    if (i + 2 + len > bytes.length || len < 1) throw new Error('the VP9 CodecPrivate feature list is malformed');
    const value = bytes[i + 2];
    if (id === 1) info.profile = value;
    if (id === 2) info.level = value;
    if (id === 3) info.bitDepth = value;
    i += 2 + len;
  }
  return info;
}

/**
 * Profile and bit depth from a VP9 keyframe's uncompressed header (frame marker, sync code, colour config).
 * @param {Uint8Array} frame
 */
export function vp9FrameInfo(frame) {
  let bit = 0;
  /** @param {number} n bits */
  const read = (n) => {
    let v = 0;
    for (let k = 0; k < n; k++, bit++) {
      if (bit >> 3 >= frame.length) throw new Error('the first VP9 frame is too short');
      v = v << 1 | (frame[bit >> 3] >> (7 - (bit & 7))) & 1;
    }
    return v;
  };
  if (read(2) !== 2) throw new Error('the first VP9 frame has no frame marker');
  const low = read(1);
  const profile = read(1) << 1 | low;
  if (profile === 3) read(1);
  if (read(1)) throw new Error('the first VP9 frame repeats an earlier frame');
  const keyframe = read(1) === 0;
  read(2); // show_frame, error_resilient_mode
  if (!keyframe) throw new Error('the first VP9 frame is not a keyframe');
  if (read(24) !== 0x498342) throw new Error('the first VP9 keyframe has no sync code');
  const bitDepth = profile >= 2 ? (read(1) ? 12 : 10) : 8;
  return { profile, bitDepth };
}

/**
 * `av01.P.LLT.DD` from an AV1CodecConfigurationRecord (av1C): profile, level, tier, bit depth.
 * @param {Uint8Array} av1C
 */
export function av1Codec(av1C) {
  need(av1C, 4, 'av1C');
  if (av1C[0] !== 0x81) throw new Error('the av1C record has no marker and version 1');
  const profile = av1C[1] >> 5;
  const level = av1C[1] & 0x1f;
  const tier = av1C[2] >> 7 ? 'H' : 'M';
  const high = (av1C[2] >> 6) & 1;
  const twelve = (av1C[2] >> 5) & 1;
  const bitDepth = high ? (twelve ? 12 : 10) : 8;
  return `av01.${profile}.${dec2(level)}${tier}.${dec2(bitDepth)}`;
}
