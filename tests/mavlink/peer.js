#!/usr/bin/env node
// The independent MAVLink peer for gpilot's tests: node-mavlink (npm, pinned by package-lock.json) reads the
// bytes gpilot-flight writes, and writes bytes for gpilot's decoder to read. No network: stdin -> stdout.
//   node peer.js decode   stdin: one hex string per line (a datagram); stdout: one JSON object per packet,
//                         then {"summary": {valid, invalid, unknown}}
//   node peer.js encode   stdin: one JSON object per line {msg, seq, sysid, compid, fields: {camelCaseName: v}}
//                         stdout: the v2 frame as one hex line
//   node peer.js table ID...  stdout: {ID: {name, crcExtra, length}} from node-mavlink's registry
'use strict';
const readline = require('readline');
const { PassThrough } = require('stream');
const { MavLinkPacketSplitter, MavLinkPacketParser, MavLinkProtocolV2, minimal, common } = require('node-mavlink');

const REGISTRY = { ...minimal.REGISTRY, ...common.REGISTRY };
const BY_NAME = Object.fromEntries(Object.values(REGISTRY).map((c) => [c.MSG_NAME, c]));
const json = (o) => JSON.stringify(o, (k, v) => (typeof v === 'bigint' ? v.toString() : v));

function lines(onLine, onEnd) {
  const rl = readline.createInterface({ input: process.stdin, terminal: false });
  rl.on('line', (l) => { if (l.trim()) onLine(l.trim()); });
  rl.on('close', onEnd);
}

function decode() {
  const input = new PassThrough();
  let crcErrors = 0;
  const splitter = new MavLinkPacketSplitter({}, { onCrcError: () => { crcErrors += 1; } });
  const reader = input.pipe(splitter).pipe(new MavLinkPacketParser());
  reader.on('data', (packet) => {
    const h = packet.header;
    const clazz = REGISTRY[h.msgid];
    const data = clazz ? packet.protocol.data(packet.payload, clazz) : null;
    // Plain field values by their registry names (COMMAND_LONG keeps params as _param1.._param7).
    const fields = {};
    if (clazz) for (const f of clazz.FIELDS) fields[f.name.replace(/^_/, '')] = data[f.name];
    process.stdout.write(json({ msg: clazz ? clazz.MSG_NAME : `UNKNOWN_${h.msgid}`, msgid: h.msgid,
      v: h.magic === 0xfd ? 2 : 1, seq: h.seq, sysid: h.sysid, compid: h.compid,
      payloadLength: h.payloadLength, fields }) + '\n');
  });
  reader.on('end', () => {
    process.stdout.write(json({ summary: { valid: splitter.validPackages, invalid: splitter.invalidPackages,
      unknown: splitter.unknownPackagesCount, crcErrors } }) + '\n');
  });
  lines((l) => input.write(Buffer.from(l, 'hex')), () => input.end());
}

function encode() {
  lines((l) => {
    const req = JSON.parse(l);
    const clazz = BY_NAME[req.msg];
    if (!clazz) throw new Error(`unknown message ${req.msg}`);
    const msg = new clazz();
    for (const [k, v] of Object.entries(req.fields || {})) msg[k] = v;
    const bytes = new MavLinkProtocolV2(req.sysid, req.compid).serialize(msg, req.seq);
    process.stdout.write(bytes.toString('hex') + '\n');
  }, () => {});
}

function table(ids) {
  const out = {};
  for (const id of ids) {
    const c = REGISTRY[id];
    out[id] = c ? { name: c.MSG_NAME, crcExtra: c.MAGIC_NUMBER, length: c.PAYLOAD_LENGTH } : null;
  }
  process.stdout.write(json(out) + '\n');
}

const mode = process.argv[2];
if (mode === 'decode') decode();
else if (mode === 'encode') encode();
else if (mode === 'table') table(process.argv.slice(3).map(Number));
else {
  process.stderr.write('usage: node peer.js decode|encode|table ID...\n');
  process.exit(2);
}
