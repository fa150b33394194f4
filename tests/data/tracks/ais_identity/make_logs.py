#!/usr/bin/python3
"""Writes the hand-made NMEA/AIS logs of this folder (issue 42). Run with /usr/bin/python3:

    /usr/bin/python3 tests/data/tracks/ais_identity/make_logs.py

AIS type 1 messages are bit-packed here (ITU-R M.1371, 8.2.4 armour), independently of shoal;
checksums are the XOR of the characters between `$`/`!` and `*`. Positions are in the Solent
(tests/data/coast/uk_solent_land.geojson): along 1.30 W southwards from 50.78 N the track
crosses the Isle of Wight (its north coast near 50.76 N at Cowes); 50.74 N, 1.05 W is open water.
"""

import os

HERE = os.path.dirname(os.path.abspath(__file__))


def checksum(body):
    x = 0
    for c in body:
        x ^= ord(c)
    return "%02X" % x


def sentence(lead, body):
    return "%s%s*%s" % (lead, body, checksum(body))


def armour(bits):
    fill = (6 - len(bits) % 6) % 6
    bits = bits + "0" * fill
    out = ""
    for i in range(0, len(bits), 6):
        v = int(bits[i:i + 6], 2)
        out += chr(v + 48 if v < 40 else v + 56)
    return out, fill


def field(v, n):
    return format(v & ((1 << n) - 1), "0%db" % n)


def type1(mmsi, lat, lon, sog_kn, cog_deg, heading_deg, second):
    bits = (field(1, 6) + field(0, 2) + field(mmsi, 30) + field(0, 4) + field(0, 8) + field(round(sog_kn * 10), 10) +
            field(1, 1) + field(round(lon * 600000), 28) + field(round(lat * 600000), 27) + field(round(cog_deg * 10), 12) +
            field(heading_deg, 9) + field(second, 6) + field(0, 2) + field(0, 3) + field(0, 1) + field(0, 19))
    assert len(bits) == 168
    return armour(bits)


def vdx(kind, mmsi, lat, lon, second, sog=8.0, cog=180.0, heading=180):
    payload, fill = type1(mmsi, lat, lon, sog, cog, heading, second)
    return sentence("!", "AI%s,1,1,,%s,%s,%d" % (kind, "" if kind == "VDO" else "A", payload, fill))


def ddmm(value, lat):
    hemi = ("N" if value >= 0 else "S") if lat else ("E" if value >= 0 else "W")
    value = abs(value)
    deg = int(value)
    minutes = (value - deg) * 60
    return ("%02d%07.4f" % (deg, minutes) if lat else "%03d%07.4f" % (deg, minutes)), hemi


def rmc(minute, second, lat=None, lon=None, status="A", date="010524", time=True):
    t = "10%02d%02d" % (minute, second) if time else ""
    if status == "A":
        la, ns = ddmm(lat, True)
        lo, ew = ddmm(lon, False)
        return sentence("$", "GPRMC,%s,A,%s,%s,%s,%s,36.0,180.0,%s,,,A" % (t, la, ns, lo, ew, date))
    return sentence("$", "GPRMC,%s,V,,,,,,,%s,,,N" % (t, date if time else ""))


def tag(epoch):
    body = "c:%d" % epoch
    return "\\%s*%s\\" % (body, checksum(body))


T0 = 1714557600  # date -u -d 2024-05-01T10:00:00Z +%s
OWN, TARGET = 235000001, 235000002


def own_lat(minute):
    return 50.78 - 0.01 * minute


def write(name, lines, note):
    with open(os.path.join(HERE, name), "w", newline="\n") as f:
        f.write("# %s\n" % note)
        for line in lines:
            f.write(line + "\n")


# 1. The own ship's RMC fixes each minute and its own !AIVDO reports: one at the half minute
# with a tag-block time, one after each RMC dated by it (the same time: held twice, kept once).
lines = []
for m in range(21):
    lines.append(rmc(m, 0, own_lat(m), -1.30))
    lines.append(vdx("VDO", OWN, own_lat(m), -1.30, 0))
    if m < 20:
        lines.append(tag(T0 + 60 * m + 30) + vdx("VDO", OWN, own_lat(m + 0.5), -1.30, 30))
    lines.append(vdx("VDM", TARGET, 50.74, -1.05 + 0.001 * m, 0, sog=3.5, cog=90.0, heading=90))
write("own_ship_rmc_and_aivdo.nmea", lines,
      "own ship 235000001: 21 RMC, 21 AIVDO dated by them, 20 AIVDO with tag-block times; target 235000002 in open water")

# 2. The GPS drops out after two minutes: RMC status V, still dated, each minute; a target's
# reports after each RMC cross the Isle of Wight.
lines = []
for m in range(21):
    lines.append(rmc(m, 0, 50.74, -1.05) if m < 2 else rmc(m, 0, status="V"))
    lines.append(vdx("VDM", TARGET, own_lat(m), -1.30, 0))
write("gps_dropout_status_v.nmea", lines,
      "RMC A at 10:00 and 10:01, then status V still dated; target 235000002 crossing the Isle of Wight, one report a minute")

# 2b. The same with the receiver's clock lost too: RMC status V without a time from 10:02.
lines = []
for m in range(21):
    lines.append(rmc(m, 0, 50.74, -1.05) if m < 2 else rmc(m, 0, status="V", time=False))
    lines.append(vdx("VDM", TARGET, own_lat(m), -1.30, 0))
write("gps_dropout_no_time.nmea", lines,
      "RMC A at 10:00 and 10:01, then status V without a time or date; target 235000002, one report a minute")

# 4. DMA $PGHP time headers, the second with month 13 (cut from dma_replay_dump.txt, line 3 edited).
lines = [
    "$PGHP,1,2013,3,18,9,19,9,499,219,,2190048,1,28*23",
    "!BSVDM,1,1,,B,14VliT002O0q2DBP:dAu7JRD0<0s,0*28",
    sentence("$", "PGHP,1,2013,13,18,9,19,10,624,219,,2190048,1,47"),
    "!BSVDM,1,1,,B,13@ni?GP?w0pFLVP7Lpv4?vF0<0h,0*47",
    "$PGHP,1,2013,3,18,9,19,10,655,219,,2190048,1,27*16",
    "!BSVDM,1,1,,A,13:Gqp0000Prm`2PJdq3`W4D059<,0*27",
]
write("pghp_month_13.txt", lines, "DMA log: the second $PGHP header has month 13")

# 5. ZDA and RMC dates that are written but impossible: ZDA day 32 at 10:05, RMC 29 February 2023
# at 10:10; the target's reports after them have no date (the log's older date must not date them).
def zda(minute, day, month, year):
    return sentence("$", "GPZDA,10%02d00.00,%s,%s,%s,00,00" % (minute, day, month, year))


lines = [
    zda(0, "01", "05", "2024"),
    vdx("VDM", TARGET, 50.74, -1.05, 0, sog=3.5, cog=90.0, heading=90),
    zda(5, "32", "05", "2024"),
    vdx("VDM", TARGET, 50.74, -1.04, 0, sog=3.5, cog=90.0, heading=90),
    rmc(10, 0, 50.75, -1.10, date="290223"),
    vdx("VDM", TARGET, 50.74, -1.03, 0, sog=3.5, cog=90.0, heading=90),
    rmc(15, 0, 50.75, -1.10),
    vdx("VDM", TARGET, 50.74, -1.02, 0, sog=3.5, cog=90.0, heading=90),
]
write("impossible_dates.nmea", lines, "ZDA 32 May 2024 at line 4, RMC 29 February 2023 at line 6: the AIS lines after each are undated")

# 6. The own ship's RMC fixes in open water and its own !AIVDO reports, dated by them, 18 km away
# on the Isle of Wight at 10:03-10:05 (a transponder fed another GPS, or another ship's).
lines = []
for m in range(8):
    lines.append(rmc(m, 0, 50.74, -1.05 - 0.002 * m))
    lines.append(vdx("VDO", OWN, 50.70 if 3 <= m <= 5 else 50.74, -1.30 if 3 <= m <= 5 else -1.05 - 0.002 * m, 0, sog=5.0, cog=270.0, heading=270))
write("own_ship_aivdo_elsewhere.nmea", lines,
      "own ship 235000001: 8 RMC in open water, an AIVDO after each; those of 10:03-10:05 on the Isle of Wight, 18 km away")
