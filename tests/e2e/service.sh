#!/bin/sh
# board/gikiosk.service is locked down: `systemd-analyze security --offline=true` scores it at most
# 2.0 (it was 8.5, EXPOSED; 0.8 when this test was written), it is Type=notify with a watchdog,
# and MemoryDenyWriteExecute stays off (llvmpipe's JIT, see the unit). The udev rules grant one
# GPIO chip and only the gpio-keys input device, never every keyboard.
. tests/e2e/lib.sh
U=board/gikiosk.service
if systemd-analyze security --help 2>/dev/null | grep -q -- '--offline'; then
    cp "$U" "$TMP/gikiosk.service"
    systemd-analyze security --offline=true "$TMP/gikiosk.service" >"$TMP/score" 2>&1
    score=$(sed -n 's/.*Overall exposure level for gikiosk.service: \([0-9.]*\).*/\1/p' "$TMP/score")
    echo "# systemd-analyze security: $score"
    check "systemd-analyze security scores the unit <= 2.0 (got '$score')" \
        awk -v s="$score" 'BEGIN { exit !(s != "" && s + 0 <= 2.0) }'
else
    ok "systemd-analyze security --offline # SKIP systemd-analyze without --offline (systemd < 250)"
fi
check "Type=notify with a WatchdogSec" sh -c "grep -qx 'Type=notify' $U && grep -qx 'WatchdogSec=[0-9]*' $U"
check "no capabilities, private network, closed device policy" \
    sh -c "grep -qx 'CapabilityBoundingSet=' $U && grep -qx 'PrivateNetwork=true' $U && grep -qx 'DevicePolicy=closed' $U"
check "MemoryDenyWriteExecute is not set (llvmpipe JITs)" sh -c "! grep -q '^MemoryDenyWriteExecute' $U"
check "the unit does not add the input group (it reads every keyboard)" sh -c "! grep -q '^SupplementaryGroups=.*input' $U"
R=board/99-gikiosk.rules
check "udev: no rule for every input event device" sh -c "! grep -v '^#' $R | grep 'SUBSYSTEM==\"input\"' | grep -vq 'gpio-keys'"
check "udev: no rule for every GPIO chip" sh -c "! grep -v '^#' $R | grep -q 'gpiochip\*'"
finish
