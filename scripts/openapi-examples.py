#!/usr/bin/env python3
"""scripts/openapi-examples.py - rewrites the /v1/simulate response examples of api/openapi.yaml from a live
daemon (tests/test_openapi.sh compares them exactly), for the request examples named on the command line.

    ./build/dashpotd --port 18977 &  python3 scripts/openapi-examples.py chain mass-matrix
"""
import json
import sys
import urllib.request

import yaml
path='api/openapi.yaml'
text=open(path).read()
doc=yaml.safe_load(text)
names=sys.argv[1:]
port=int(__import__('os').environ.get('PORT','18977'))
post=doc['paths']['/v1/simulate']['post']
reqs=post['requestBody']['content']['application/json']['examples']
resp=post['responses']['200']['content']
lines=text.split('\n')
def fetch(body, media):
    r=urllib.request.Request(f'http://127.0.0.1:{port}/v1/simulate', data=json.dumps(body).encode(), headers={'Accept':media,'Content-Type':'application/json'})
    return urllib.request.urlopen(r).read().decode()
# find line ranges: within the responses 200 content section, per media type, per name
def find_block(media, name):
    # locate media line after 'responses:' of /v1/simulate
    start=None
    for i,l in enumerate(lines):
        if l.strip()=="/v1/simulate:": start=i; break
    i=start
    while not lines[i].strip().startswith("'200'") and not lines[i].strip().startswith('"200"') and not lines[i].strip().startswith("200:"): i+=1
    while lines[i].strip()!=media+':': i+=1
    while lines[i].strip()!=name+':': i+=1
    ind=len(lines[i])-len(lines[i].lstrip())
    j=i+1
    while j<len(lines) and (lines[j].strip()=='' or len(lines[j])-len(lines[j].lstrip())>ind): j+=1
    # keep trailing blank lines outside
    k=j
    while lines[k-1].strip()=='' : k-=1
    return i,k,ind
for name in names:
    body=reqs[name]['value']
    for media in ['application/json','application/x-ndjson','text/event-stream','text/csv']:
        out=fetch(body, media)
        i,k,ind=find_block(media,name)
        pad=' '*(ind+2)
        if media=='application/json':
            new=[lines[i], pad+'value: '+json.dumps(json.loads(out), ensure_ascii=False)]
        else:
            style='|+' if out.endswith('\n\n') else '|'
            body_lines=out.split('\n')
            if body_lines and body_lines[-1]=='': body_lines=body_lines[:-1]
            if style=='|+':
                while body_lines and body_lines[-1]=='': body_lines=body_lines[:-1]
                pass
            new=[lines[i], pad+'value: '+style]+[(pad+'  '+b) if b else '' for b in body_lines]
        lines[i:k]=new
open(path,'w').write('\n'.join(lines))
