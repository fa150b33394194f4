"""Writes the hostile zips of this folder (the same bytes on every run): /usr/bin/python3 make_zips.py

dotdot_member.zip: vessel 222222222 clear of land in `clear.csv`; vessel 111111111 sailing south
across the Isle of Wight (it grounds) in `../grounds.csv`, a member whose name climbs out of the
zip's folder (GDAL does not list it); `sub/../hidden.csv`, which GDAL cannot read at all.
macos.zip: the same two vessels in `clear.csv` and `grounds.csv`, each with the resource fork
macOS's Finder adds (`__MACOSX/._clear.csv`, `__MACOSX/._grounds.csv`: AppleDouble bytes, not CSV).
"""
import os
import zipfile

HERE = os.path.dirname(os.path.abspath(__file__))
HEADER = "mmsi,timestamp,lat,lon,sog,cog,heading\n"


def row(mmsi, minute, lat, lon):
    return "%s,2024-05-01T10:%02d:00Z,%.4f,%.4f,11.9,180,511\n" % (mmsi, minute, lat, lon)


GROUNDS = HEADER + "".join(row("111111111", i, 50.78 - 0.01 * i, -1.30) for i in range(21))
CLEAR = HEADER + "".join(row("222222222", i, 50.74, -1.05 + 0.002 * i) for i in range(11))
FORK = b"\x00\x05\x16\x07\x00\x02\x00\x00Mac OS X        \x00\x02" + b"\x00" * 24


def write(name, members):
    with zipfile.ZipFile(os.path.join(HERE, name), "w", zipfile.ZIP_DEFLATED) as z:
        for member, data in members:
            info = zipfile.ZipInfo(member, date_time=(2024, 5, 1, 12, 0, 0))
            info.compress_type = zipfile.ZIP_DEFLATED
            info.external_attr = 0o644 << 16
            z.writestr(info, data)


write("dotdot_member.zip", [("clear.csv", CLEAR), ("../grounds.csv", GROUNDS), ("sub/../hidden.csv", CLEAR)])
write("macos.zip", [("clear.csv", CLEAR), ("grounds.csv", GROUNDS), ("__MACOSX/._clear.csv", FORK), ("__MACOSX/._grounds.csv", FORK)])
