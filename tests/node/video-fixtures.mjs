// Small videos for the demuxer and WebCodecs tests, made at test time with ffmpeg from its
// `testsrc` pattern (never committed), and what ffprobe says about them.
import { execFileSync } from 'node:child_process';
import { mkdtempSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';

export const FRAMES = 37;
export const FPS = 25;

const X264 = ['-c:v', 'libx264', '-profile:v', 'high', '-level', '3.0', '-bf', '2', '-g', '12'];
const VP9 = ['-c:v', 'libvpx-vp9', '-deadline', 'realtime', '-cpu-used', '8', '-g', '12'];
const AV1 = ['-c:v', 'libaom-av1', '-cpu-used', '8', '-g', '12'];

/** File name -> ffmpeg output options. Each is FRAMES frames at FPS of 160x120. */
export const VIDEOS = {
  'vp9.webm': [...VP9, '-pix_fmt', 'yuv420p'],
  'vp9-10bit.webm': [...VP9, '-pix_fmt', 'yuv420p10le'],
  'vp8.webm': ['-c:v', 'libvpx', '-g', '12', '-pix_fmt', 'yuv420p'],
  'av1.webm': [...AV1, '-pix_fmt', 'yuv420p'],
  'h264.mkv': [...X264, '-pix_fmt', 'yuv420p'],
  'h264.mp4': [...X264, '-pix_fmt', 'yuv420p'],
  'h264-faststart.mp4': [...X264, '-pix_fmt', 'yuv420p', '-movflags', '+faststart'],
  'vp9.mp4': [...VP9, '-pix_fmt', 'yuv420p'],
  'av1.mp4': [...AV1, '-pix_fmt', 'yuv420p'],
  'hevc.mp4': ['-c:v', 'libx265', '-x265-params', 'log-level=error:keyint=12', '-tag:v', 'hvc1', '-pix_fmt', 'yuv420p'],
  'mpeg4.mp4': ['-c:v', 'mpeg4', '-pix_fmt', 'yuv420p'],
};

/**
 * Frame k of a `ramp` is flat grey of luma 16 + 5k (limited range): about 5.82 k in RGB, so a
 * frame's index can be read from any pixel.
 */
export const RAMP_STEP = 255 / 219 * 5;

/**
 * Makes `names` (keys of VIDEOS) in a new temporary folder, from `testsrc` or, with `ramp`,
 * the grey ramp; returns { dir, path(name) }.
 */
export function makeVideos(names = Object.keys(VIDEOS), { size = '160x120', frames = FRAMES, fps = FPS, ramp = false } = {}) {
  const dir = mkdtempSync(join(tmpdir(), 'lanepf-videos-'));
  const input = ramp ? `color=c=black:s=${size}:r=${fps},format=yuv420p,geq=lum='16+5*N':cb=128:cr=128`
    : `testsrc=size=${size}:rate=${fps}`;
  for (const name of names) {
    execFileSync('ffmpeg', ['-v', 'error', '-y', '-f', 'lavfi', '-i', input,
      '-frames:v', `${frames}`, ...VIDEOS[name], join(dir, name)]);
  }
  return { dir, path: (name) => join(dir, name) };
}

function probe(path, args) {
  return JSON.parse(execFileSync('ffprobe', ['-v', 'error', '-select_streams', 'v:0', '-of', 'json', ...args, path]));
}

/** The number of frames ffmpeg decodes from the video stream (`ffprobe -count_frames`). */
export function countFrames(path) {
  return Number(probe(path, ['-count_frames', '-show_entries', 'stream=nb_read_frames']).streams[0].nb_read_frames);
}

/** The video packets in file order: { pts (µs), key, size }. */
export function packets(path) {
  return probe(path, ['-show_entries', 'packet=pts_time,flags,size']).packets.map((p) => ({
    pts: Math.round(Number(p.pts_time) * 1e6), key: p.flags.includes('K'), size: Number(p.size),
  }));
}

/** The stream's profile and level as ffprobe names them. */
export function streamInfo(path) {
  return probe(path, ['-show_entries', 'stream=profile,level,extradata_size']).streams[0];
}
