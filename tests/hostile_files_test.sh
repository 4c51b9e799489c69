#!/usr/bin/env bash
# Input is data: files that go through GDAL or name other files (elevation models, VRTs, airspace
# files), written as an adversary would, must not read a file the scenario was not pointed at,
# reach the network, crash, block or exhaust the machine: each is refused with one line naming
# the file (exit 2) within the time limit, or loads as data. A listener on 127.0.0.1 counts every
# connection the tool makes. Also the limits around them: deep JSON, fence values, the plan's
# size, the space-time lattice, `bench mapf` on a large instance, KML text XML cannot hold.
# Usage: hostile_files_test.sh UAVPLAN_BINARY SOURCE_DIR [TIME_SCALE]
# TIME_SCALE multiplies every time limit (a sanitizer build runs several times slower).
set -u
BIN=$1
SRC=$2
SCALE=${3:-1}
TMP=$(mktemp -d)
LISTENER_PID=
trap 'rm -rf "$TMP"; [ -n "$LISTENER_PID" ] && kill "$LISTENER_PID" 2>/dev/null' EXIT
fails=0
pass=0
ok() { pass=$((pass + 1)); }
bad() { echo "FAIL $1"; fails=$((fails + 1)); }

# A listener on a free loopback port: it counts connections in $TMP/connections and ends by
# itself after 300 s.
python3 - "$TMP" <<'EOF' &
import os, socket, sys, time
tmp = sys.argv[1]
s = socket.socket(); s.bind(("127.0.0.1", 0)); s.listen(16); s.settimeout(0.2)
open(os.path.join(tmp, "port.tmp"), "w").write(str(s.getsockname()[1])); os.rename(os.path.join(tmp, "port.tmp"), os.path.join(tmp, "port"))
n, end = 0, time.time() + 300
while time.time() < end:
    try:
        c, _ = s.accept(); n += 1; open(os.path.join(tmp, "connections"), "w").write(str(n)); c.close()
    except socket.timeout:
        pass
EOF
LISTENER_PID=$!
for _ in $(seq 50); do [ -f "$TMP/port" ] && break; sleep 0.1; done
PORT=$(cat "$TMP/port")

D=$TMP/s
mkdir -p "$D"
# A 4 x 4 ASCII grid in CH1903 / LV03 (EPSG:21781) round the scenario's origin, and its CRS.
cat >"$D/src.asc" <<'EOF'
ncols 4
nrows 4
xllcorner 780000
yllcorner 186000
cellsize 100
NODATA_value -9999
1 2 3 4
5 6 7 8
9 10 11 12
13 14 15 16
EOF
gdalsrsinfo -o wkt1 --single-line EPSG:21781 >"$D/src.prj" 2>/dev/null
# scenario NAME TERRAIN_OR_AIRSPACE_LINE [HALF_WIDTH]: a scenario over the grid (bounds +-100 m
# or +-HALF_WIDTH) naming one file.
scenario() {
  local h=${3:-100}
  cat >"$D/$1.yaml" <<EOF
version: 1
origin: {lat: 46.80256, lon: 9.79959, alt: 0}
world:
  bounds: {min: [-$h, -$h, 0], max: [$h, $h, 300]}
$2
uavs:
  - {id: a, start: [-50, -50, 200], goal: [50, 50, 200]}
EOF
}
vrt() {  # vrt FILE BAND_ATTRS SOURCE_XML [SIZE]
  cat >"$1" <<EOF
<VRTDataset rasterXSize="${4:-4}" rasterYSize="${4:-4}">
  <SRS>EPSG:21781</SRS>
  <GeoTransform>780000, 100, 0, 186400, 0, -100</GeoTransform>
  <VRTRasterBand dataType="Float32" band="1"$2>
    $3
  </VRTRasterBand>
</VRTDataset>
EOF
}
simple() { echo "<SimpleSource><SourceFilename relativeToVRT=\"$2\">$1</SourceFilename><SourceBand>1</SourceBand></SimpleSource>"; }
# refused NAME SCENARIO PART [SECONDS]: exit 2 within SECONDS (default 5), one line naming PART.
refused() {
  local name=$1 file=$2 part=$3 limit=${4:-5} t0 t1 rc
  rm -rf "$TMP/out"
  t0=$(date +%s.%N)
  timeout 30 "$BIN" plan "$file" -o "$TMP/out" --time-limit 1 --max-memory 512M >/dev/null 2>"$TMP/stderr"
  rc=$?
  t1=$(date +%s.%N)
  if [ "$rc" != 2 ]; then bad "$name: exit $rc, expected 2: $(head -c 300 "$TMP/stderr")"; return; fi
  if [ "$(wc -l <"$TMP/stderr")" != 1 ] || ! grep -qF -- "$part" "$TMP/stderr"; then
    bad "$name: stderr is not one line with '$part': $(head -c 400 "$TMP/stderr")"; return
  fi
  if [ -e "$TMP/out" ]; then bad "$name: wrote output"; return; fi
  if ! python3 -c "import sys; sys.exit(0 if $t1 - $t0 <= $limit * $SCALE else 1)"; then bad "$name: took more than $limit s (x $SCALE)"; return; fi
  ok
}

# The control: a VRT of plain sources inside the folder loads and plans.
vrt "$D/ok.vrt" "" "$(simple src.asc 1)"
scenario ok "  terrain: {file: ok.vrt}"
"$BIN" plan "$D/ok.yaml" -o "$TMP/ok" >/dev/null 2>"$TMP/stderr" && ok || bad "vrt.plain: $(cat "$TMP/stderr")"

# 1. Raw bands read any file's bytes as heights (/proc/self/environ, /etc/passwd).
vrt "$D/raw.vrt" ' subClass="VRTRawRasterBand"' '<SourceFilename relativetoVRT="0">/proc/self/environ</SourceFilename>'
scenario raw "  terrain: {file: raw.vrt}"
refused vrt.raw_environ "$D/raw.yaml" "VRTRawRasterBand"
vrt "$D/passwd.vrt" "" "$(simple /etc/passwd 0)"
scenario passwd "  terrain: {file: passwd.vrt}"
refused vrt.absolute_source "$D/passwd.yaml" "a source must be a path relative to the VRT"
vrt "$D/up.vrt" "" "$(simple ../../../etc/passwd 1)"
scenario up "  terrain: {file: up.vrt}"
refused vrt.parent_source "$D/up.yaml" "without '..'"
ln -s /etc/passwd "$D/link.asc"
vrt "$D/link.vrt" "" "$(simple link.asc 1)"
scenario link "  terrain: {file: link.vrt}"
refused vrt.link_out "$D/link.yaml" "leads out of"
ln -s /proc/self/environ "$D/environ.asc"
scenario environ "  terrain: {file: environ.asc}"
refused terrain.kernel_file "$D/environ.yaml" "is empty"
vrt "$D/pixfn.vrt" ' subClass="VRTDerivedRasterBand"' "<PixelFunctionType>sum</PixelFunctionType>$(simple src.asc 1)"
scenario pixfn "  terrain: {file: pixfn.vrt}"
refused vrt.pixel_function "$D/pixfn.yaml" "VRTDerivedRasterBand"

# 2. The network: a /vsicurl/ source, a KML that is an OGR VRT naming one; no connection made.
vrt "$D/curl.vrt" "" "$(simple "/vsicurl/http://127.0.0.1:$PORT/dem.tif" 0)"
scenario curl "  terrain: {file: curl.vrt}"
refused vrt.vsicurl "$D/curl.yaml" "relative to the VRT"
vrt "$D/curl2.vrt" "" "$(simple "/vsicurl/http://127.0.0.1:$PORT/dem.tif" 1)"
scenario curl2 "  terrain: {file: curl2.vrt}"
refused vrt.vsicurl_relative "$D/curl2.yaml" "/vsi"
cat >"$D/ogr.kml" <<EOF
<OGRVRTDataSource><OGRVRTLayer name="z"><SrcDataSource>/vsicurl/http://127.0.0.1:$PORT/z.csv</SrcDataSource></OGRVRTLayer></OGRVRTDataSource>
EOF
scenario ogrkml "  airspace: [{file: ogr.kml}]"
refused kml.ogr_vrt "$D/ogrkml.yaml" "ogr.kml"
"$BIN" info "$D/curl.yaml" >/dev/null 2>&1
"$BIN" info "$D/ogrkml.yaml" >/dev/null 2>&1
sleep 0.5
if [ -s "$TMP/connections" ]; then bad "network: $(cat "$TMP/connections") connections reached 127.0.0.1:$PORT"; else ok; fi

# 3. MEM::: sources (a pointer into the process: SIGSEGV).
vrt "$D/mem.vrt" "" "$(simple 'MEM:::DATAPOINTER=0x1000,PIXELS=4,LINES=4,DATATYPE=Float32' 1)"
scenario mem "  terrain: {file: mem.vrt}"
refused vrt.mem_pointer "$D/mem.yaml" "MEM:::"

# 4. FIFOs: a VRT source, a sidecar GDAL would open, an OGR VRT in a KML.
mkfifo "$D/fifo.asc"
vrt "$D/fifo.vrt" "" "$(simple fifo.asc 1)"
scenario fifo "  terrain: {file: fifo.vrt}"
refused vrt.fifo_source "$D/fifo.yaml" "not a regular file" 3
cp "$D/src.asc" "$D/side.asc" && cp "$D/src.prj" "$D/side.prj" && mkfifo "$D/side.asc.aux.xml"
scenario side "  terrain: {file: side.asc}"
refused terrain.fifo_sidecar "$D/side.yaml" "sidecar" 3
cat >"$D/fifo.kml" <<EOF
<OGRVRTDataSource><OGRVRTLayer name="z"><SrcDataSource>$D/fifo.asc</SrcDataSource></OGRVRTLayer></OGRVRTDataSource>
EOF
scenario fifokml "  airspace: [{file: fifo.kml}]"
refused kml.fifo "$D/fifokml.yaml" "fifo.kml" 3

# 5. Deep JSON: 100,000 nested objects in an airspace file's properties.
python3 -c "
d = 100000
print('{\"type\":\"Feature\",\"properties\":' + '{\"a\":' * d + '1' + '}' * d + ',\"geometry\":null}')" >"$D/deep.geojson"
scenario deep "  airspace: [{file: deep.geojson}]"
refused json.deep_properties "$D/deep.yaml" "nest more than"

# 6. Rasters within the limits: a sparse 100,000 x 100,000 GeoTIFF, a VRT of the same size.
gdal_create -of GTiff -outsize 100000 100000 -ot Float32 -co SPARSE_OK=YES -co TILED=YES -co COMPRESS=DEFLATE \
  -a_srs EPSG:21781 -a_ullr 730000 236000 830000 136000 "$D/sparse.tif" >/dev/null 2>&1
scenario sparse "  terrain: {file: sparse.tif}" 40000
refused raster.sparse_huge "$D/sparse.yaml" "window of" 1.5
vrt "$D/huge.vrt" "" "$(simple src.asc 1)" 100000
sed -i 's|780000, 100, 0, 186400, 0, -100|779000, 0.02, 0, 187000, 0, -0.02|' "$D/huge.vrt"
scenario huge "  terrain: {file: huge.vrt}" 700
refused raster.huge_vrt "$D/huge.yaml" "window of" 1.5

# 7. Values that are no heights or places: a NaN geotransform, -3.4e38 heights, a floor of -1e300
# m, a .kml that is not KML.
sed 's|780000, 100, 0, 186400, 0, -100|nan, 100, 0, 186400, 0, -100|' "$D/ok.vrt" >"$D/nan.vrt"
scenario nan "  terrain: {file: nan.vrt}"
refused raster.nan_geotransform "$D/nan.yaml" "geotransform"
sed 's/^1 2 3 4$/-3.4e38 2 3 4/; /NODATA/d' "$D/src.asc" >"$D/low.asc" && cp "$D/src.prj" "$D/low.prj"
scenario low "  terrain: {file: low.asc}"
refused raster.float_min_heights "$D/low.yaml" "beyond +-1e9 m"
cat >"$D/floor.geojson" <<'EOF'
{"type": "Feature", "properties": {"floor_m": -1e300},
 "geometry": {"type": "Polygon", "coordinates": [[[9.7995, 46.8025], [9.7998, 46.8025], [9.7998, 46.8027], [9.7995, 46.8025]]]}}
EOF
scenario floor "  airspace: [{file: floor.geojson}]"
refused airspace.floor_huge "$D/floor.yaml" "floor_m"
echo '{"not": "kml"}' >"$D/notkml.kml"
scenario notkml "  airspace: [{file: notkml.kml}]"
refused kml.not_kml "$D/notkml.yaml" "notkml.kml"

# 8. QGC fence values with the file and the place.
echo '{"geoFence": {"circles": [{"inclusion": false, "circle": {"center": [46.8025, 9.7995], "radius": 1e300}}]}}' \
  >"$D/radius.plan"
scenario radius "  airspace: [{file: radius.plan}]"
refused fence.radius_huge "$D/radius.yaml" "geoFence.circles[0].circle.radius"
echo '{"geoFence": {"polygons": {"a": 1}}}' >"$D/object.plan"
scenario object "  airspace: [{file: object.plan}]"
refused fence.polygons_object "$D/object.yaml" "geoFence.polygons"

# 9. Loads and plans within their size: a 100,000-vertex prism, a home 1e6 s of flight away.
python3 - "$D/prism.yaml" <<'EOF'
import math, sys
n = 100000
pts = ", ".join("[%.3f, %.3f]" % (500 + 200 * math.cos(2 * math.pi * k / n), 500 + 200 * math.sin(2 * math.pi * k / n)) for k in range(n))
open(sys.argv[1], "w").write("""version: 1
world:
  bounds: {min: [0, 0, 0], max: [1000, 1000, 100]}
  obstacles: [{type: prism, polygon: [%s], z_min: 0, z_max: 100}]
uavs:
  - {id: a, start: [50, 50, 50], goal: [950, 950, 50]}
""" % pts)
EOF
# The file itself takes yaml-cpp about a second to parse (`info` measures the load alone); past
# the load nothing may run more than 0.5 s past the limit. Measured in CPU seconds (user + system
# of the process): wall time on a machine busy with the other tests varies by more than that.
cpu_run() {  # cpu_run CMD...: prints "EXIT CPU_SECONDS"
  python3 -c 'import resource, subprocess, sys
rc = subprocess.run(sys.argv[1:], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, timeout=30).returncode
r = resource.getrusage(resource.RUSAGE_CHILDREN)
print(rc, r.ru_utime + r.ru_stime)' "$@"
}
load_s=0.0
for _ in 1 2; do  # the longer of two loads
  read -r _ cpu < <(cpu_run "$BIN" info "$D/prism.yaml")
  load_s=$(python3 -c "print(max($load_s, $cpu))")
done
read -r rc plan_s < <(cpu_run "$BIN" plan "$D/prism.yaml" -o "$TMP/prism" --time-limit 1)
if [ "$rc" -le 1 ] && python3 -c "import sys; sys.exit(0 if $plan_s <= $load_s + 0.5 * $SCALE and $load_s < 4 * $SCALE else 1)"; then ok; else
  bad "prism.100k: exit $rc after $(python3 -c "print(round($plan_s, 2))") CPU s with --time-limit 1 (load alone $load_s CPU s)"; fi
cat >"$D/home.yaml" <<'EOF'
version: 1
world: {bounds: {min: [-1e7, -1e7, 0], max: [1e7, 1e7, 100]}}
uavs:
  - {id: a, start: [0, 0, 50], goal: [100, 0, 50], home: [-9e6, 0, 0], speed: 10}
EOF
refused plan.home_far "$D/home.yaml" "from its home and back"

# 10. A space-time lattice spacing too small is bad input naming the key.
rm -rf "$TMP/out"
"$BIN" plan "$SRC/tests/data/deconfliction/swap6.yaml" -o "$TMP/out" --set space_time_cell_m=0.001 \
  --set deconfliction=space_time >/dev/null 2>"$TMP/stderr"
rc=$?
if [ "$rc" = 2 ] && grep -q "space_time_cell_m" "$TMP/stderr" && [ ! -e "$TMP/out" ]; then ok; else bad "space_time_cell_m.tiny: exit $rc: $(cat "$TMP/stderr")"; fi

# 11. KML export of names holding U+FFFE / U+FFFF: well-formed XML.
cat >"$D/names.yaml" <<'EOF'
version: 1
name: "odd \uFFFE name \uFFFF"
origin: {lat: 46.8, lon: 9.8, alt: 1500}
world:
  bounds: {min: [0, 0, 0], max: [200, 200, 60]}
  obstacles: [{id: "box \uFFFF", type: box, min: [80, 80, 0], max: [120, 120, 60]}]
uavs:
  - {id: "u \uFFFE", start: [10, 10, 20], goal: [190, 190, 20]}
EOF
"$BIN" plan "$D/names.yaml" -o "$TMP/names" --export kml >/dev/null 2>"$TMP/stderr" || bad "kml.noncharacters plan: $(cat "$TMP/stderr")"
if python3 -c "
import glob, sys, xml.dom.minidom
for f in glob.glob(sys.argv[1] + '/*.kml'): xml.dom.minidom.parse(f)
sys.exit(0 if glob.glob(sys.argv[1] + '/*.kml') else 1)" "$TMP/names" 2>"$TMP/xmlerr"; then ok; else bad "kml.noncharacters: $(cat "$TMP/xmlerr" | tail -1)"; fi

# 12. bench mapf on one 250-agent 1024 x 1024 instance ends near its limit, one instance read at a time.
mkdir -p "$TMP/mapf"
python3 - "$TMP/mapf/big_agents250.yaml" <<'EOF'
import random, sys
random.seed(3); n = 1024
cells = random.sample(range(n * n), 500)
lines = ["agents:"]
for k in range(250):
    s, g = cells[2 * k], cells[2 * k + 1]
    lines += ["-   goal: [%d, %d]" % (g % n, g // n), "    name: agent%d" % k, "    start: [%d, %d]" % (s % n, s // n)]
lines += ["map:", "    dimensions: [%d, %d]" % (n, n), "    obstacles: []"]
open(sys.argv[1], "w").write("\n".join(lines) + "\n")
EOF
t0=$(date +%s.%N)
timeout 60 "$BIN" bench mapf "$TMP/mapf" --time-limit 1 >/dev/null 2>&1
t1=$(date +%s.%N)
python3 -c "import sys; sys.exit(0 if $t1 - $t0 <= 8 * $SCALE else 1)" && ok || bad "mapf.large: $(python3 -c "print(round($t1 - $t0, 1))") s with --time-limit 1"

# 13. Ctrl-C while a large window is read: the read stops between strips (exit 130, within 2 s;
# it took 20 s when the window was read whole).
scenario big "  terrain: {file: sparse.tif}" 19000
"$BIN" plan "$D/big.yaml" -o "$TMP/big" >/dev/null 2>&1 &
pid=$!
sleep 1
t0=$(date +%s.%N)
kill -INT $pid
wait $pid
rc=$?
t1=$(date +%s.%N)
if [ "$rc" = 130 ] && python3 -c "import sys; sys.exit(0 if $t1 - $t0 <= 2.0 * $SCALE else 1)" && [ ! -e "$TMP/big" ]; then ok; else
  bad "raster.interrupt: exit $rc after $(python3 -c "print(round($t1 - $t0, 2))") s"; fi

# Our own: ten more files an adversary would write.
# a. A VRT naming itself (GDAL meets its own open again), b. a warped VRT (<SourceDataset>), c. a
# vrt:// source, d. a terrain link to /dev/zero, e. a VRT of 5,000 sources naming one file.
vrt "$D/self.vrt" "" "$(simple self.vrt 1)"
scenario self "  terrain: {file: self.vrt}"
refused own.vrt_self "$D/self.yaml" "self.vrt"
cat >"$D/warp.vrt" <<'EOF'
<VRTDataset rasterXSize="4" rasterYSize="4" subClass="VRTWarpedDataset"><SRS>EPSG:21781</SRS>
<GeoTransform>780000, 100, 0, 186400, 0, -100</GeoTransform><GDALWarpOptions><SourceDataset relativeToVRT="1">src.asc</SourceDataset></GDALWarpOptions></VRTDataset>
EOF
scenario warp "  terrain: {file: warp.vrt}"
refused own.vrt_warped "$D/warp.yaml" "VRTWarpedDataset"
vrt "$D/vrtscheme.vrt" "" "$(simple 'vrt://src.asc?bands=1' 1)"
scenario vrtscheme "  terrain: {file: vrtscheme.vrt}"
refused own.vrt_scheme "$D/vrtscheme.yaml" "vrt://"
ln -s /dev/zero "$D/zero.tif"
scenario zero "  terrain: {file: zero.tif}"
refused own.link_dev_zero "$D/zero.yaml" "zero.tif"
python3 -c "
s = ''.join('<SimpleSource><SourceFilename relativeToVRT=\"1\">src.asc</SourceFilename><SourceBand>1</SourceBand></SimpleSource>' for _ in range(5000))
print('<VRTDataset rasterXSize=\"4\" rasterYSize=\"4\"><SRS>EPSG:21781</SRS><GeoTransform>780000, 100, 0, 186400, 0, -100</GeoTransform><VRTRasterBand dataType=\"Float32\" band=\"1\">' + s + '</VRTRasterBand></VRTDataset>')" >"$D/many.vrt"
scenario many "  terrain: {file: many.vrt}"
t0=$(date +%s.%N)
timeout 30 "$BIN" info "$D/many.yaml" >/dev/null 2>"$TMP/stderr"
rc=$?
t1=$(date +%s.%N)
if [ "$rc" = 0 ] && python3 -c "import sys; sys.exit(0 if $t1 - $t0 <= 5 * $SCALE else 1)"; then ok; else
  bad "own.vrt_many_sources: exit $rc in $(python3 -c "print(round($t1 - $t0, 1))") s: $(cat "$TMP/stderr")"; fi
# f. A KML NetworkLink to the listener, g. an external entity naming /etc/passwd, h. entities
# that expand a billion times: no connection, no file's text, no hang.
cat >"$D/link.kml" <<EOF
<?xml version="1.0" encoding="UTF-8"?><kml xmlns="http://www.opengis.net/kml/2.2"><Document>
<NetworkLink><Link><href>http://127.0.0.1:$PORT/zones.kml</href></Link></NetworkLink>
<Placemark><name>z</name><Polygon><outerBoundaryIs><LinearRing><coordinates>9.7995,46.8025 9.7998,46.8025 9.7998,46.8027 9.7995,46.8025</coordinates></LinearRing></outerBoundaryIs></Polygon></Placemark></Document></kml>
EOF
scenario netlink "  airspace: [{file: link.kml}]"
timeout 30 "$BIN" info "$D/netlink.yaml" >/dev/null 2>&1
cat >"$D/xxe.kml" <<'EOF'
<?xml version="1.0" encoding="UTF-8"?><!DOCTYPE kml [<!ENTITY x SYSTEM "file:///etc/passwd">]>
<kml xmlns="http://www.opengis.net/kml/2.2"><Document><Placemark><name>&x;</name>
<Polygon><outerBoundaryIs><LinearRing><coordinates>9.7995,46.8025 9.7998,46.8025 9.7998,46.8027 9.7995,46.8025</coordinates></LinearRing></outerBoundaryIs></Polygon></Placemark></Document></kml>
EOF
scenario xxe "  airspace: [{file: xxe.kml}]"
timeout 30 "$BIN" info "$D/xxe.yaml" >"$TMP/xxe.out" 2>&1
if grep -q "root:" "$TMP/xxe.out"; then bad "own.kml_external_entity: /etc/passwd's text reached the output"; else ok; fi
python3 - "$D/laughs.kml" <<'EOF'
import sys
ents = '<!ENTITY l0 "lol">' + ''.join('<!ENTITY l%d "%s">' % (k, ('&l%d;' % (k - 1)) * 10) for k in range(1, 10))
open(sys.argv[1], "w").write('<?xml version="1.0"?><!DOCTYPE kml [%s]><kml xmlns="http://www.opengis.net/kml/2.2"><Document>'
  '<Placemark><name>&l9;</name></Placemark></Document></kml>' % ents)
EOF
scenario laughs "  airspace: [{file: laughs.kml}]"
t0=$(date +%s.%N)
timeout 30 "$BIN" plan "$D/laughs.yaml" -o "$TMP/laughs" --time-limit 1 >/dev/null 2>&1
rc=$?
t1=$(date +%s.%N)
if [ "$rc" != 124 ] && python3 -c "import sys; sys.exit(0 if $t1 - $t0 <= 3 * $SCALE else 1)"; then ok; else
  bad "own.kml_laughs: exit $rc in $(python3 -c "print(round($t1 - $t0, 1))") s"; fi
sleep 0.3
if [ -s "$TMP/connections" ]; then bad "own.kml_network_link: $(cat "$TMP/connections") connections reached 127.0.0.1:$PORT"; else ok; fi
# i. An airspace file that is a FIFO, j. an ESRI .bil whose header claims 10^9 x 10^9 pixels.
mkfifo "$D/zones.geojson"
scenario fifozones "  airspace: [{file: zones.geojson}]"
refused own.airspace_fifo "$D/fifozones.yaml" "zones.geojson" 3
printf 'NROWS 1000000000\nNCOLS 1000000000\nNBANDS 1\nNBITS 32\nPIXELTYPE FLOAT\nBYTEORDER I\nULXMAP 700000\nULYMAP 280000\nXDIM 0.0001\nYDIM 0.0001\n' >"$D/wide.hdr"
head -c 4096 /dev/zero >"$D/wide.bil" && cp "$D/src.prj" "$D/wide.prj"
scenario wide "  terrain: {file: wide.bil}"
refused own.ehdr_huge_header "$D/wide.yaml" "wide.bil"

echo "$pass passed, $fails failed"
[ "$fails" = 0 ]
