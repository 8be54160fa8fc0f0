#!/usr/bin/env python3
"""What identifying a record's pulse costs (issue 42 item 4: a study's [outputs] record_pulses).

    PYTHONPATH=build/python python3 bench/pulse_cost.py --library LIB.csv [--repeat 3]

LIB.csv is a table of `pcrf record spectra` (it lists every component and every pair it found);
each pair is classified by Shahi & Baker (2014) and each component alone by Baker (2007) with
`pcrf.pulse` (the engine's classify_station_pulse, the study's code), in this process. CPU time
(time.process_time, this process only, so other load does not count) per record, the median of
`--repeat` calls, which includes reading the AT2 files (a few ms at most). Prints a table per
method (records, samples, median and largest CPU per record) and the total for the library: a
study with record_pulses pays it once, in the master, before the cube is created.
"""
import argparse
import csv
import statistics
import time

import pcrf


def cpu_of(call, repeat):
    times = []
    for _ in range(repeat):
        start = time.process_time()
        result = call()
        times.append(time.process_time() - start)
    return statistics.median(times), result


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument('--library', required=True)
    p.add_argument('--repeat', type=int, default=3)
    args = p.parse_args()
    rows = list(csv.DictReader(line for line in open(args.library) if not line.startswith('#')))
    runs = {'shahi-baker-2014 (pairs)': [], 'baker-2007 (components)': []}
    refused = []
    for r in rows:
        pair = r['kind'] == 'rotd50'
        call = (lambda: pcrf.pulse(r['file'], record_h2=r['file_h2'])) if pair else (lambda: pcrf.pulse(r['file']))
        try:
            cpu, result = cpu_of(call, args.repeat)
        except pcrf.InputError as e:  # a pair whose files state no azimuths: a study refuses it too
            refused.append('%s: %s' % (r['name'], e))
            continue
        runs['shahi-baker-2014 (pairs)' if pair else 'baker-2007 (components)'].append(
            (cpu, int(r['samples']), result['pulse_like']))
    for line in refused:
        print('left out:', line)
    print('| method | records | pulse-like | samples (median, largest) | CPU per record: median [ms] | largest [ms] | total [s] |')
    print('| --- | --- | --- | --- | --- | --- | --- |')
    for method, items in runs.items():
        if not items:
            continue
        cpus = [c for c, _, _ in items]
        samples = [n for _, n, _ in items]
        print('| %s | %d | %d | %d, %d | %.0f | %.0f | %.2f |' % (
            method, len(items), sum(1 for _, _, like in items if like), statistics.median(samples), max(samples),
            1e3 * statistics.median(cpus), 1e3 * max(cpus), sum(cpus)))


if __name__ == '__main__':
    main()
