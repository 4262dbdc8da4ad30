# size-report.awk - flash and RAM per module of the firmware image, from the linker's map
# files (what really went into the image, after --gc-sections), against the budgets.
#   awk -f size-report.awk MODULES.map [IMAGE.map]
# MODULES.map is a link without LTO (LTO merges the modules, so its map cannot tell them
# apart): the per-module figures. IMAGE.map is the image that ships (with LTO): the exact
# figures checked against the budgets. With one map, both come from it.
# Flash = code, read-only data and the initial values of .data/.tdata; RAM = .data,
# .tdata, .tbss, .bss and the stack.
# The budgets (issue 31): 192 KB of the LM3S6965's 256 KB of flash, all its 64 KB of RAM.
BEGIN { FLASH_BUDGET = 192 * 1024; RAM_BUDGET = 64 * 1024; inmap = 0; nfile = 0 }
FNR == 1 { nfile++; inmap = 0; out = ""; pending = 0 }
/^Linker script and memory map/ { inmap = 1; next }
!inmap { next }
# An output section: remember where its input sections go, and its exact size (the
# per-module figures count merged strings before merging, so their sum is a little high).
/^\.[A-Za-z_]/ {
    out = $1
    if ($3 ~ /^0x/) osize[nfile, out] = strtonum_hex($3)
    next
}
nfile > 1 { next }
# An input section whose name was too long: its address, size and file are on the next line.
/^ [.A-Z][^ ]*$/ { pending = 1; next }
/^ [.A-Z]/ || (pending && /^  +0x/) {
    n = split($0, f, /[ \t]+/)
    # fields: "" name addr size file   or (continued line) "" addr size file
    if (pending) { addr = f[2]; size = f[3]; file = f[4] } else { addr = f[3]; size = f[4]; file = f[5] }
    pending = 0
    if (size !~ /^0x/ || file == "") next
    bytes = strtonum_hex(size)
    if (bytes == 0) next
    mod = module(file)
    if (out == ".text") flash[mod] += bytes
    else if (out == ".data" || out == ".tdata") { flash[mod] += bytes; ram[mod] += bytes }
    else if (out == ".bss" || out == ".tbss") ram[mod] += bytes
    mods[mod] = 1
    next
}
function strtonum_hex(s,    v, i, c) {
    v = 0; s = tolower(s); sub(/^0x/, "", s)
    for (i = 1; i <= length(s); i++) { c = index("0123456789abcdef", substr(s, i, 1)) - 1; v = v * 16 + c }
    return v
}
function module(file,    m) {
    if (file ~ /lib(c|m)\.a\(/ ) return "C library (picolibc)"
    if (file ~ /libgcc\.a\(/) return "compiler runtime (libgcc)"
    m = file; sub(/.*\//, "", m); sub(/\.o$/, "", m)
    return m
}
function image_flash(k) { return osize[k, ".text"] + osize[k, ".data"] + osize[k, ".tdata"] }
function image_ram(k) {
    return osize[k, ".data"] + osize[k, ".tdata"] + osize[k, ".tbss_space"] + osize[k, ".bss"] + osize[k, ".stack"]
}
function verdict(used, budget) { return used <= budget ? "within" : "OVER" }
END {
    ram["main stack"] += osize[1, ".stack"]; mods["main stack"] = 1
    printf "%-28s %8s %8s\n", "module (link without LTO)", "flash", "RAM"
    cmd = "sort -t'|' -k2,2nr | awk -F'|' '{ printf \"%-28s %8d %8d\\n\", $1, $2, $3 }'"
    for (m in mods) { printf "%s|%d|%d\n", m, flash[m], ram[m] | cmd; tf += flash[m]; tr += ram[m] }
    close(cmd)
    printf "%-28s %8d %8d\n", "sum of the modules", tf, tr
    printf "%-28s %8d %8d\n", "image without LTO (exact)", image_flash(1), image_ram(1)
    imgf = image_flash(nfile); imgr = image_ram(nfile)
    printf "%-28s %8d %8d\n", (nfile > 1 ? "image with LTO (exact)" : "image (exact)"), imgf, imgr
    printf "%-28s %8d %8d\n", "budget", FLASH_BUDGET, RAM_BUDGET
    printf "flash %d bytes, %.1f %% of its budget: %s (%+d bytes)\n", imgf, 100 * imgf / FLASH_BUDGET,
        verdict(imgf, FLASH_BUDGET), FLASH_BUDGET - imgf
    printf "RAM %d bytes, %.1f %% of its budget: %s (%+d bytes)\n", imgr, 100 * imgr / RAM_BUDGET,
        verdict(imgr, RAM_BUDGET), RAM_BUDGET - imgr
    print "dictionary: at least 16384 bytes free for programs asked; the firmware prints what it has"
    print "  at boot, and qemu_cm3_plan fails below 16384"
}
